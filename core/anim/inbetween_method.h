#pragma once
// How the animation passes from one key to the next when both have one connectivity (Alexa 2002, ch. 4):
//  - handles: the handle transforms are interpolated (rotation-aware, interpolate.h) and skinned: the rig's
//    own in-between (pose keys only; between mesh keys the prism build blends vertices linearly);
//  - arap: the two keyed meshes are interpolated as rigidly as possible (4.4, arap_interpolation.h), so a
//    bending or turning limb keeps its shape;
//  - linear: the vertices are blended linearly (what the prism build does between two layers).
// Plain names only (scene files read them; the fuzzed scene reader links no animation code).
#include <string>

namespace dfm {

enum class InbetweenMethod { Handles, Arap, Linear };

const char* inbetween_method_name(InbetweenMethod m);  // "handles", "arap", "linear"
// Throws dfm::Error naming the word and the choices.
InbetweenMethod parse_inbetween_method(const std::string& word);

}  // namespace dfm
