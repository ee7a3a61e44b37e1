// Linked into every test that can bind: the process-wide numeric settings a program sets before it
// binds (core/bind/numeric_setup.h), as deform and deform-editor do in main().
#include "core/bind/numeric_setup.h"

namespace {
const bool numerics_ready = (dfm::setup_numerics(), true);
}  // namespace
