// 2D instruction-driven image editors for semantic editing: the paper uses
// InstructPix2Pix. Three adapters:
//   - command:  an external program run through /bin/sh from a template such as
//               "prog {in} {out} {instruction}" ({mask} and {view} are also replaced;
//               every value is shell-quoted). The program reads the PNG at {in} and
//               writes a PNG or JPEG to {out}.
//   - http:     POST to an http:// endpoint (see docs/semantic.md for the request and
//               response), e.g. InstructPix2Pix served on a GPU host.
//   - builtin:  deterministic offline editors for tests and demos (NOT InstructPix2Pix):
//               "builtin:recolor" recolours the selected region with the colour named in
//               the instruction ("gold", "red", ...), "builtin:recolor=r,g,b" with that
//               colour; "builtin:grayscale" removes the region's colour. Both keep the
//               region's shading (luminance) and leave every other pixel unchanged.
// A failing or timed-out editor throws Error with the editor, the view and the reason.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"

namespace isegman::edit {

struct EditRequest {
  const Image* image = nullptr;  // 3 channels, [0, 1]
  const Image* mask = nullptr;   // optional 1 channel: the selection's coverage in this view
  std::string instruction;
  std::string view;              // view name, for messages and the {view} placeholder
};

class ImageEditor {
 public:
  virtual ~ImageEditor() = default;
  virtual std::string describe() const = 0;
  // Returns the edited image at the input's size (other sizes are resized back).
  virtual Image edit(const EditRequest& request) = 0;
};

// "builtin:recolor", "builtin:recolor=r,g,b", "builtin:grayscale"; throws otherwise.
std::unique_ptr<ImageEditor> make_builtin_editor(const std::string& spec);
std::unique_ptr<ImageEditor> make_command_editor(const std::string& command_template, double timeout_s);
// url: http://host[:port][/path]. https is not supported (tunnel it, e.g. ssh -L).
std::unique_ptr<ImageEditor> make_http_editor(const std::string& url, double timeout_s);

// The colour the builtin recolour editor picks for an instruction; false when it names
// none of its colours.
bool instruction_color(const std::string& instruction, float rgb[3], std::string* word = nullptr);

// Helpers exposed for tests.
std::string shell_quote(const std::string& s);
std::string base64_encode(const uint8_t* data, size_t size);
std::vector<uint8_t> base64_decode(const std::string& text, const std::string& source);

}  // namespace isegman::edit
