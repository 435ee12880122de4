// The .splat reader/writer lives in io/splat.h (every command loads through io); these
// names keep edit's callers compiling.
#pragma once

#include "io/splat.h"

namespace isegman::edit {

using isegman::kSplatRecordBytes;
using isegman::parse_splat;
using isegman::read_splat;
using isegman::serialize_splat;
using isegman::splat_f32;
using isegman::write_splat;

}  // namespace isegman::edit
