// Linked into every test that can bind: the process-wide numeric settings a program makes before it
// binds (core/bind/numeric_setup.h), the two steps deform and deform-editor take in main.
#include "core/bind/numeric_setup.h"

DFM_RUN_OPENMP_REGIONS_SERIALLY()

namespace {
const bool numerics_ready = (dfm::setup_numerics(), true);
}  // namespace
