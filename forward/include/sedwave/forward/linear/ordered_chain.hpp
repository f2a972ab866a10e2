#pragma once
// An ordered chain as a channel packing: n unit grains (diameter 1, mass 1) on the z axis, each
// pressed into its neighbours by `spacing` < 1, between a one-grain lower (driven) wall and a
// one-grain upper wall, in a periodic box wide enough that no images touch. Its exact dynamics is
// the lattice theory (theory/lattice.hpp), which makes it the reference case of the linear engine
// and the medium in which an absorbing layer's reflection can be measured exactly.
#include "sedwave/forward/channel/preparation.hpp"

namespace sedwave::forward::linear {

[[nodiscard]] channel::PreparedChannel ordered_chain(int n, double spacing);

}  // namespace sedwave::forward::linear
