// What a path synthesized falls short of, in sentences for the user: a segment past the path's
// end (asked for, but no frame can carry it), a rest asked for at the end standing more than
// kEndReachedM from it or facing more than kRestFacingWarnDeg off the path's last direction, the
// end not reached (and why, as far as can be told), dawdling, following the path further off than
// the retries look for, a motion type asked for and missed (and, in a segment too short for the
// retries to judge, one asked for and played in none of its frames). The CLI's `path` prints them as
// warnings, the Python package raises them as UserWarning, the studio shows them; the report
// carries them ("shortfalls"). Each but the rest's facing is what synthesize_path's retries judged
// the kept attempt by.
#pragma once

#include <string>
#include <vector>

#include "motiongraph/synthesis/floor_path.h"
#include "motiongraph/synthesis/path_synthesis.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

constexpr double kRestFacingWarnDeg = 45.0;

// One sentence per shortfall, in the order above; none for a result the retries would keep
// of a path whose segments it reaches.
std::vector<std::string> path_shortfalls(const SynthesisContext& context, const FloorPath& path,
                                         const PathSynthesisSettings& settings, const PathSynthesisResult& result);

}  // namespace mg
