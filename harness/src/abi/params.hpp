// params.hpp — a plugin's parameters as the host carries them: name → value text, validated against
// the plugin's table (abi/instances.hpp validate_params) before any plugin sees them.
#pragma once

#include <map>
#include <string>

namespace vobench {

using ParamMap = std::map<std::string, std::string>;

}  // namespace vobench
