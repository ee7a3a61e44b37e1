// Precompiled once and reused by every test executable (tests/CMakeLists.txt): Catch2, Eigen's dense
// headers and the standard headers most tests include are most of a test file's parse time (CI budget).
// Only third-party and standard headers here, so a test still names everything it uses itself.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <catch2/catch.hpp>
