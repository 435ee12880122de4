// Options shared by `segment`, `eval` and the ablation: SAM files, views, propagation,
// voting and inspection settings.
#pragma once

#include <memory>
#include <set>
#include <string>

#include "app/args.h"
#include "models/sam.h"
#include "segment/session.h"
#include "segment/views.h"

namespace isegman::app {

struct SegmentSetup {
  segment::SessionOptions session;
  segment::ViewOptions views;
  std::string views_spec = "auto";  // every camera up to 20, else 20 chosen for the click
  std::string sam_dir;
};

const std::set<std::string>& segment_value_flags();
const std::set<std::string>& segment_switch_flags();
SegmentSetup parse_segment_setup(const Args& args);
std::shared_ptr<const models::SamModel> load_sam(const SegmentSetup& setup);
// $ISEGMAN_CACHE_DIR, else $XDG_CACHE_HOME/isegman, else ~/.cache/isegman.
std::string default_cache_dir();
// Text of the options for usage messages.
extern const char* const kSegmentOptionsHelp;

}  // namespace isegman::app
