#include "record/criterion.hpp"

#include "metrics/metric_catalog.hpp"

#include <regex>
#include <stdexcept>

namespace vobench {

Criterion parse_criterion(const std::string& text) {
    static const std::regex form(R"(^\s*([a-z_.]+)\s*(<=|>=|==|<|>)\s*([-+0-9.eE]+)\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, form)) throw std::invalid_argument("criterion '" + text + "' is not of the form 'metric <= number'");
    if (metrics::find_metric(m[1].str()) == nullptr)
        throw std::invalid_argument("criterion '" + text + "': unknown metric '" + m[1].str() + "'");
    Criterion c;
    c.metric = m[1];
    c.op = m[2];
    try {
        c.value = std::stod(m[3]);
    } catch (const std::exception&) {
        throw std::invalid_argument("criterion '" + text + "': '" + m[3].str() + "' is not a number");
    }
    c.text = text;
    return c;
}

}  // namespace vobench
