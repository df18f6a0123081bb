// integer_normals.h — internal to fast/src/global: double normals along an exact direction
// that no rounded unit vector represents, for the offers of suspect_proof.cpp and
// global_depth.cpp's report_shallow.
//
// Input : y, an exact non-zero direction; `tries`, consecutive integers c to try; `keep`, how
//         many to return (at most 8).
// Output: appended to out, best first: double triples (integers below 2^53) whose directions
//         are nearest y's among those tried. Only a search: each triple is evaluated by the caller.
#pragma once

#include <vector>

#include "global/vec3.h"
#include "exact/exact_geometry.h"

namespace pdd::fast::global {

void integer_normals(const detail::Q (&y)[3], int tries, int keep, std::vector<V3>& out);

}  // namespace pdd::fast::global
