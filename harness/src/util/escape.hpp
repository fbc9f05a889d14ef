// escape.hpp — every string that reaches a script, table or page passes through one of these, chosen
// by the target. Names, reasons and versions come from configs, plugins, data folders and results
// folders, so any of them may hold newlines, quotes, backslashes, `$(…)`, `<script>`, `\input{…}`,
// `=cmd|…`, invalid UTF-8 or right-to-left marks. Each function returns text that is inert in its
// target: it can change how a name looks, never what the target does.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

namespace vobench {

// Valid UTF-8: every invalid byte sequence becomes U+FFFD; C0 controls other than tab, DEL, C1
// controls and the bidirectional overrides/isolates (U+202A–U+202E, U+2066–U+2069, which can make a
// name read backwards) become U+FFFD too unless `keep_newlines` (then \n and \t stay).
std::string clean_text(std::string_view text, bool keep_newlines = false);

// A gnuplot single-quoted string literal, quotes included. Nothing inside '…' is interpreted by
// gnuplot (no backquote, macro or backslash expansion); the newline that would end the statement is
// replaced, and an apostrophe is shown as U+2019 (gnuplot's '' escape is not reliable).
std::string gnuplot_quoted(std::string_view text);

// A Markdown table cell or heading text: | \ ` * _ [ ] < > # and friends backslash-escaped (so no
// inline HTML, links or code spans), newlines as spaces.
std::string markdown_text(std::string_view text);

// LaTeX body text: the ten special characters as their text commands, newlines as spaces, so that
// neither \input, \write18 nor a stray } can come through.
std::string latex_text(std::string_view text);
// A LaTeX comment line's text (after %): newlines become spaces, so the comment cannot end early.
std::string latex_comment(std::string_view text);

// One CSV field (RFC 4180): always quoted, quotes doubled; a field that a spreadsheet would run as a
// formula (starting with = + - @, tab or carriage return) gets a leading apostrophe (OWASP's rule).
std::string csv_field(std::string_view text);

// HTML text or attribute value: & < > " ' as entities.
std::string html_text(std::string_view text);

// A file-name stem that is readable and unique: [a-z0-9._-] kept (others '-'), cut to 48 characters,
// then '-' and 8 hex digits of a hash of the whole original name. Two different names never share a
// stem unless their 64-bit hashes' first 32 bits collide.
std::string file_stem(std::string_view name);
// The same for a name made of parts (kind, entry, sequence, sensor): the slug joins them with '_',
// the hash covers each part and its length, so ("a_b", "c") and ("a", "b_c") differ.
std::string file_stem(std::initializer_list<std::string_view> parts);

}  // namespace vobench
