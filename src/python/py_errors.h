#pragma once
// One-line errors: amrvk's own errors are bad input (ValueError) unless they come from the device
// or the runtime, which raise RuntimeError through their own types.
#include "python/arguments.h"

namespace amrvk::python {

// Registers the translator from C++ exceptions to Python's: gpu::ShaderCompileError ->
// RuntimeError, amrvk::Error -> ValueError (its CLI option names as keywords), std::bad_alloc ->
// MemoryError, a cast error -> TypeError; each one line, bytes that are not UTF-8 shown as \xNN.
void bindErrors();

}  // namespace amrvk::python
