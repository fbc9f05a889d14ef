// The metric catalogue is the one list of names: configs/README.md documents exactly these, and every
// name is unique and has a unit.
#include "metrics/metric_catalog.hpp"
#include "util/files.hpp"

#include <catch2/catch.hpp>

#include <regex>
#include <set>
#include <sstream>

using namespace vobench;

TEST_CASE("configs/README.md lists exactly the catalogue's metric names", "[metrics][catalog]") {
    const std::string readme = read_file(std::string(VOBENCH_SOURCE_DIR) + "/configs/README.md");
    const auto start = readme.find("Metric names");
    REQUIRE(start != std::string::npos);
    const std::string paragraph = readme.substr(start, readme.find("\n\n", start) - start);
    // Backticked groups hold one or several names: `ate.rmse ate.mean …`, `failed_cells`.
    std::set<std::string> documented;
    const std::regex group("`([a-z_. ]+)`");
    for (auto it = std::sregex_iterator(paragraph.begin(), paragraph.end(), group); it != std::sregex_iterator(); ++it) {
        std::istringstream words((*it)[1].str());
        for (std::string w; words >> w;) documented.insert(w);
    }
    std::set<std::string> catalogue;
    for (const auto& m : metrics::metric_catalog()) {
        CHECK_FALSE(m.unit.empty());
        CHECK(catalogue.insert(m.name).second);
    }
    CHECK(documented == catalogue);
}

TEST_CASE("the catalogue knows direction, combination and ground-truth kind", "[metrics][catalog]") {
    REQUIRE(metrics::find_metric("fps"));
    CHECK(metrics::find_metric("fps")->better == metrics::Better::higher);
    CHECK(metrics::find_metric("ate.rmse")->better == metrics::Better::lower);
    CHECK(metrics::find_metric("failed_cells")->combine == metrics::Combine::sum);
    CHECK(metrics::find_metric("rpe.rot.rmse")->accuracy == metrics::GtAccuracy::rotation);
    CHECK(metrics::find_metric("rpe.trans.rmse")->accuracy == metrics::GtAccuracy::position);
    CHECK(metrics::find_metric("no.such") == nullptr);
}
