// placeholder replaced below
#include "engine/cli/commands.hpp"
namespace hapscene { int test_command(std::vector<std::string>) { return 1; } }
