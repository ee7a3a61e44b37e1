// Precompiled once per core/, render/ and app/ target (cmake/DeformHelpers.cmake): Eigen and the
// standard headers most sources include are much of a source's parse time (CI budget). Only
// third-party and standard headers here, so a source still names everything it uses itself.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/Sparse>
