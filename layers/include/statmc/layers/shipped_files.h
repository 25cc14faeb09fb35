// What ships beside statmc's programs under PREFIX/lib/statmc (the plugin modules, the
// isolated decoder), found relative to the running program so that a build tree or an
// installed prefix can be moved as a whole.
#pragma once

#include <string>
#include <vector>

namespace statmc::layers {

/// The existing paths of `name` shipped with statmc, in search order, for the running
/// program: beside it (a build tree's programs) and PREFIX/lib/statmc/NAME from
/// PREFIX/bin; from the Python module at PREFIX/lib/pythonX.Y/*-packages/statmc,
/// PREFIX/lib/statmc/NAME. `build_fallback` (the build tree's path, for programs that sit
/// elsewhere: the tests, the Python module in the build tree) is used when none exists.
std::vector<std::string> shipped_paths(const std::string& name,
                                       const std::string& build_fallback = {});

}  // namespace statmc::layers
