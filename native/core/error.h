// The native core's error types. The core never exits, aborts or prints: it throws one of these, and the
// boundary (Python module, CLI) turns them into a Python exception or an exit status.
#pragma once

#include <stdexcept>
#include <string>

namespace candela {

/// The scene data is malformed (bad array shape, index out of range, non-finite vertex, ...).
struct InvalidScene : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A render parameter has the wrong type or an unsupported value.
struct InvalidParameter : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The render was cancelled by the user; not an error, unwinds work quietly.
struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("cancelled") {}
};

/// A broken invariant inside Candela (a bug) or a failure of a library (Embree, OpenEXR).
struct InternalError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace candela
