// First look at a request's header block, before cpp-httplib reads the body: a bad,
// negative or oversized Content-Length is answered at once (400/413) instead of after a
// read timeout, and a body-carrying method without a length gets "Content-Length: 0"
// (curl -X POST sends none; the API's no-body endpoints must still work).
#pragma once

#include <cstddef>
#include <string>

namespace isegman::server {

struct HeadCheck {
  int status = 0;        // 0: pass it on; else answer with this status and `message`
  std::string message;
  bool add_zero_length = false;  // insert "Content-Length: 0" after the request line
};

// `head`: the bytes up to and including the blank line ending the headers.
HeadCheck check_request_head(const std::string& head, size_t max_body_bytes);

}  // namespace isegman::server
