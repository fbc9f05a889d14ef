#include "util/escape.hpp"

#include "util/hash.hpp"

#include <cctype>
#include <cstdint>
#include <cstdio>

namespace vobench {

namespace {

constexpr const char* kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// Length of the valid UTF-8 sequence starting at s[i] and its code point, or 0 when it is invalid
// (overlong forms, surrogates and values past U+10FFFF included).
std::size_t utf8_sequence(std::string_view s, std::size_t i, uint32_t& cp) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
    const unsigned char c = b(0);
    std::size_t n = 0;
    if (c < 0x80) {
        cp = c;
        return 1;
    }
    if (c >= 0xC2 && c <= 0xDF) {
        n = 2;
        cp = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        cp = c & 0x0F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        cp = c & 0x07;
    } else
        return 0;
    if (i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((b(k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (b(k) & 0x3F);
    }
    if ((n == 3 && cp < 0x800) || (n == 4 && (cp < 0x10000 || cp > 0x10FFFF)) || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

bool is_bidi_control(uint32_t cp) {
    return (cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069) || cp == 0x200E || cp == 0x200F;
}

// clean_text, then each ASCII character through `ascii` (which appends its escaped form).
template <typename Ascii>
std::string map_clean(std::string_view text, Ascii ascii) {
    const std::string clean = clean_text(text);
    std::string out;
    out.reserve(clean.size() + 8);
    for (char c : clean) {
        if (static_cast<unsigned char>(c) >= 0x80)
            out += c;
        else
            ascii(out, c);
    }
    return out;
}

}  // namespace

std::string clean_text(std::string_view text, bool keep_newlines) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        uint32_t cp = 0;
        const std::size_t n = utf8_sequence(text, i, cp);
        if (n == 0) {
            out += kReplacement;
            ++i;
            continue;
        }
        const bool control = cp < 0x20 || cp == 0x7F || (cp >= 0x80 && cp < 0xA0);
        if ((control && !(keep_newlines && (cp == '\n' || cp == '\t'))) || is_bidi_control(cp)) {
            out += cp == '\n' || cp == '\r' || cp == '\t' ? std::string(" ") : std::string(kReplacement);
        } else {
            out.append(text.substr(i, n));
        }
        i += n;
    }
    return out;
}

std::string gnuplot_quoted(std::string_view text) {
    // gnuplot's '' escape is not reliable (four quotes in a row break its scanner), so a title's
    // apostrophe is shown as U+2019 and the literal holds no quote at all.
    return "'" + map_clean(text, [](std::string& out, char c) { out += c == '\'' ? std::string("\xE2\x80\x99") : std::string(1, c); }) +
           "'";
}

std::string markdown_text(std::string_view text) {
    const std::string clean = clean_text(text);
    const auto word = [&](std::size_t k) {
        return k < clean.size() && (std::isalnum(static_cast<unsigned char>(clean[k])) || static_cast<unsigned char>(clean[k]) >= 0x80);
    };
    std::string out;
    for (std::size_t i = 0; i < clean.size(); ++i) {
        const char c = clean[i];
        // An underscore inside a word never starts emphasis (CommonMark), so put_vo stays readable.
        const bool intraword_underscore = c == '_' && i > 0 && word(i - 1) && word(i + 1);
        if (std::string_view("\\`*_[]<>|~&$").find(c) != std::string_view::npos && !intraword_underscore) out += '\\';
        out += c;
    }
    return out;
}

std::string latex_text(std::string_view text) {
    return map_clean(text, [](std::string& out, char c) {
        switch (c) {
            case '\\': out += "\\textbackslash{}"; break;
            case '~': out += "\\textasciitilde{}"; break;
            case '^': out += "\\textasciicircum{}"; break;
            case '<': out += "\\textless{}"; break;
            case '>': out += "\\textgreater{}"; break;
            case '|': out += "\\textbar{}"; break;
            case '"': out += "\\textquotedbl{}"; break;
            case '_':
            case '&':
            case '%':
            case '#':
            case '$':
            case '{':
            case '}':
                out += '\\';
                out += c;
                break;
            default: out += c;
        }
    });
}

std::string latex_comment(std::string_view text) { return clean_text(text); }

std::string csv_field(std::string_view text) {
    std::string clean = clean_text(text);
    if (!clean.empty() && (clean[0] == '=' || clean[0] == '+' || clean[0] == '-' || clean[0] == '@')) clean.insert(0, "'");
    std::string out = "\"";
    for (char c : clean) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string html_text(std::string_view text) {
    return map_clean(text, [](std::string& out, char c) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    });
}

namespace {

std::string stem_from(std::string_view name, const Hasher& h) {
    std::string slug;
    for (char c : name) {
        if (slug.size() >= 48) break;
        const auto u = static_cast<unsigned char>(c);
        if ((u >= 'a' && u <= 'z') || (u >= '0' && u <= '9') || c == '.' || c == '_' || c == '-')
            slug += c;
        else if (u >= 'A' && u <= 'Z')
            slug += static_cast<char>(u - 'A' + 'a');
        else if (slug.empty() || slug.back() != '-')
            slug += '-';
    }
    while (!slug.empty() && slug.front() == '.') slug.erase(0, 1);  // never a hidden file, never ".."
    while (!slug.empty() && (slug.back() == '-' || slug.back() == '_')) slug.pop_back();
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(h.value() >> 32));
    return (slug.empty() ? std::string("x") : slug) + "-" + hex;
}

}  // namespace

std::string file_stem(std::string_view name) {
    Hasher h;
    h.add(name.data(), name.size());
    return stem_from(name, h);
}

std::string file_stem(std::initializer_list<std::string_view> parts) {
    Hasher h;
    std::string joined;
    for (std::string_view p : parts) {
        const uint64_t size = p.size();
        h.add(&size, sizeof size);
        h.add(p.data(), p.size());
        if (!p.empty()) joined += (joined.empty() ? "" : "_") + std::string(p);
    }
    return stem_from(joined, h);
}

}  // namespace vobench
