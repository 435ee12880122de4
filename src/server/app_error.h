// The errors of the app below the HTTP layer: a kind (what went wrong, in the app's
// words) and a message naming the input. The API layer (api.cc) maps kinds to status
// codes; nothing below it knows about HTTP.
#pragma once

#include <string>

#include "core/error.h"

namespace isegman::server {

enum class ErrorKind {
  kInvalid,      // the request is malformed or out of range
  kNotFound,     // it names something that does not exist (a tool, a thumbnail)
  kConflict,     // not possible in the current state (nothing selected, nothing to undo)
  kUnavailable,  // the feature is off or not ready (segmentation without SAM)
  kBusy,         // the job queue is full or stopped: try again later
};

class AppError : public Error {
 public:
  AppError(ErrorKind kind, const std::string& message) : Error(message), kind_(kind) {}
  ErrorKind kind() const { return kind_; }

 private:
  ErrorKind kind_;
};

[[noreturn]] inline void invalid(const std::string& message) { throw AppError(ErrorKind::kInvalid, message); }
[[noreturn]] inline void conflict(const std::string& message) { throw AppError(ErrorKind::kConflict, message); }

}  // namespace isegman::server
