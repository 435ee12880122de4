// The error a request handler throws to answer with a 4xx/5xx status and a message.
// Handlers validate every input and throw HttpError(400, "...") naming the field and the
// problem; the API layer turns it into {"error": message} with that status.
#pragma once

#include <stdexcept>
#include <string>

namespace isegman::server {

class HttpError : public std::runtime_error {
 public:
  HttpError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

[[noreturn]] inline void bad_request(const std::string& message) { throw HttpError(400, message); }

}  // namespace isegman::server
