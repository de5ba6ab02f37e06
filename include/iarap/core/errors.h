// Typed exceptions thrown at the library's boundary (readers, *_precompute, CLI, HTTP).
// Every message names the file:line or the element at fault.
#pragma once
#include <stdexcept>
#include <string>

namespace iarap {

// Base of every error iarap throws on purpose.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Malformed or unreadable input: files, constraint sets, arguments, arrays.
class InputError : public Error {
public:
  using Error::Error;
};

// A mesh the algorithms cannot work on: non-manifold, NaN coordinates, degenerate beyond repair.
class TopologyError : public Error {
public:
  using Error::Error;
};

// The numerical solve cannot proceed: singular system, unconstrained component, failed factorization.
class SolverError : public Error {
public:
  using Error::Error;
};

} // namespace iarap
