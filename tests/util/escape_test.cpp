// The hostile-string corpus through every escaping function of util/escape.hpp: each output must be
// inert in its target. gnuplot is run for real on a script that carries every string as a title.
#include "util/escape.hpp"
#include "util/files.hpp"
#include "util/subprocess.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string>& hostile() {
    static const std::vector<std::string> corpus = {
        "plain",
        "new\nline",
        "carriage\rreturn",
        "quote ' and '' and \"double\"",
        "back\\slash \\\\ \\n",
        "$(touch PWNED_sh) `touch PWNED_bt`",
        "'; system(\"touch PWNED_gp\"); print '",
        "\nsystem(\"touch PWNED_gp2\")\n",
        "; rm -rf / ;",
        "<script>alert(1)</script>",
        "<img src=x onerror=alert(1)>",
        "\\input{/etc/passwd}",
        "\\write18{touch PWNED_tex}",
        "} \\end{document}",
        "=cmd|' /C calc'!A0",
        "+1+2",
        "-2+3",
        "@SUM(A1:A2)",
        "\tTAB",
        "| a | b |",
        "[link](javascript:alert(1))",
        "*bold* _it_ `code`",
        "\xff\xfe invalid \xc0\x80 utf8 \xed\xa0\x80",
        "right\xe2\x80\xaeto-left \xe2\x81\xa6isolate",
        "nul\x01\x02\x7f controls",
        "émoji 😀 ü",
        std::string(4096, 'x'),
        std::string("null\0byte", 9),
    };
    return corpus;
}

bool valid_utf8(const std::string& s) {
    try {
        return nlohmann::json::parse(nlohmann::json(s).dump()).is_string();
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace

TEST_CASE("clean_text gives valid UTF-8 without controls or bidi overrides", "[util][escape]") {
    for (const std::string& s : hostile()) {
        const std::string c = clean_text(s);
        CHECK(valid_utf8(c));
        for (unsigned char ch : c) CHECK((ch >= 0x20 && ch != 0x7f));
        CHECK(c.find("\xe2\x80\xae") == std::string::npos);
        CHECK(c.find("\xe2\x81\xa6") == std::string::npos);
    }
    CHECK(clean_text("émoji 😀") == "émoji 😀");
    CHECK(clean_text("a\nb", true) == "a\nb");
}

TEST_CASE("gnuplot: every hostile title is one string literal, and gnuplot runs none of it", "[util][escape][gnuplot]") {
    for (const std::string& s : hostile()) {
        const std::string q = gnuplot_quoted(s);
        REQUIRE(q.size() >= 2);
        CHECK(q.front() == '\'');
        CHECK(q.back() == '\'');
        CHECK(q.find('\n') == std::string::npos);
        // No quote inside: the literal cannot end early.
        CHECK(q.substr(1, q.size() - 2).find('\'') == std::string::npos);
    }
    const fs::path dir = fs::temp_directory_path() / "vobench-escape-gnuplot";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string script = "set terminal dumb\nset output 'plot.txt'\n";
    for (const std::string& s : hostile()) script += "set title " + gnuplot_quoted(s) + "\nplot x title " + gnuplot_quoted(s) + "\n";
    script += "set print 'done.txt'\nprint 'finished'\n";
    write_file_atomic(dir / "hostile.gp", script);
    ChildResult r;
    try {
        r = run_program({"sh", "-c", "cd '" + dir.string() + "' && gnuplot hostile.gp"}, 60);
    } catch (const std::exception&) {}
    if (!(r.exited && r.exit_code == 0) && r.output.find("not found") != std::string::npos) {
        WARN("gnuplot is not installed: the run of the hostile script was skipped");
        return;
    }
    INFO(r.output);
    CHECK(r.exited);
    CHECK(r.exit_code == 0);
    CHECK(fs::exists(dir / "done.txt"));  // the script ran to its end: no title broke a statement
    for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().rfind("PWNED", 0) != 0);
}

TEST_CASE("Markdown: no newline, no unescaped |, no inline HTML, links or code spans", "[util][escape]") {
    for (const std::string& s : hostile()) {
        const std::string m = markdown_text(s);
        CHECK(m.find('\n') == std::string::npos);
        for (std::size_t i = 0; i < m.size(); ++i)
            if (m[i] == '|' || m[i] == '<' || m[i] == '>' || m[i] == '`' || m[i] == '[' || m[i] == '*') {
                REQUIRE(i > 0);
                CHECK(m[i - 1] == '\\');
            }
        CHECK(valid_utf8(m));
    }
    CHECK(markdown_text("put_vo") == "put_vo");  // intraword underscores stay readable
    CHECK(markdown_text("_x_") == "\\_x\\_");
}

TEST_CASE("LaTeX: only the text commands of the escaping, never \\input or \\write18", "[util][escape]") {
    const std::set<std::string> allowed = {"textbackslash", "textasciitilde", "textasciicircum", "textless",
                                           "textgreater",   "textbar",        "textquotedbl"};
    for (const std::string& s : hostile()) {
        const std::string t = latex_text(s);
        CHECK(t.find('\n') == std::string::npos);
        const std::regex command(R"(\\([A-Za-z]+))");
        for (auto it = std::sregex_iterator(t.begin(), t.end(), command); it != std::sregex_iterator(); ++it)
            CHECK(allowed.count((*it)[1]) == 1);
        // Braces only as the {} after a text command, or escaped.
        const std::string stripped =
            std::regex_replace(std::regex_replace(t, std::regex(R"(\\[A-Za-z]+\{\})"), ""), std::regex(R"(\\[{}])"), "");
        CHECK(stripped.find('{') == std::string::npos);
        CHECK(stripped.find('}') == std::string::npos);
        CHECK(latex_comment(s).find('\n') == std::string::npos);
    }
}

TEST_CASE("CSV: one quoted field, quotes doubled, no formula", "[util][escape]") {
    for (const std::string& s : hostile()) {
        const std::string f = csv_field(s);
        REQUIRE(f.size() >= 2);
        CHECK(f.front() == '"');
        CHECK(f.back() == '"');
        const std::string inner = f.substr(1, f.size() - 2);
        CHECK(std::regex_replace(inner, std::regex("\"\""), "").find('"') == std::string::npos);
        CHECK(inner.find('\n') == std::string::npos);
        if (!inner.empty()) CHECK(std::string("=+-@").find(inner[0]) == std::string::npos);
    }
    CHECK(csv_field("=1+1") == "\"'=1+1\"");
}

TEST_CASE("HTML: no markup survives", "[util][escape]") {
    for (const std::string& s : hostile()) {
        const std::string h = html_text(s);
        for (char c : {'<', '>', '"', '\''}) CHECK(h.find(c) == std::string::npos);
        CHECK(valid_utf8(h));
    }
}

TEST_CASE("JSON: invalid UTF-8 is replaced, never thrown", "[util][escape]") {
    nlohmann::json j = nlohmann::json::array();
    for (const std::string& s : hostile()) j.push_back(s);
    std::string text;
    REQUIRE_NOTHROW(text = json_text(j));
    CHECK(nlohmann::json::parse(text).size() == hostile().size());
}

TEST_CASE("file stems: readable, safe and unique per name", "[util][escape]") {
    std::set<std::string> stems;
    for (const std::string& s : hostile()) {
        const std::string stem = file_stem(s);
        CHECK(std::regex_match(stem, std::regex("[a-z0-9._-]{1,48}-[0-9a-f]{8}")));
        CHECK(stem.front() != '.');
        stems.insert(stem);
    }
    CHECK(stems.size() == hostile().size());
    // Names that differ only where the slug cannot show it (case, non-ASCII, length past 48) differ.
    CHECK(file_stem("Put_VO") != file_stem("put_vo"));
    CHECK(file_stem("ü") != file_stem("ö"));
    CHECK(file_stem(std::string(60, 'a') + "1") != file_stem(std::string(60, 'a') + "2"));
    CHECK(file_stem({"a_b", "c"}) != file_stem({"a", "b_c"}));
}
