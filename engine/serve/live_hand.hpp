#pragma once
// POST /api/hand: on a simulated device the page's pointer takes the hand toward a point
// of the workspace ({"x_m": X}, with "y_m" on a 2-DOF device), or lets it go
// ({"release": true}). A point outside the running version's workspace is refused.
#include <string>

#include "engine/devices/hand_pointer.hpp"
#include "engine/serve/live_document.hpp"

namespace hapscene {

// `pointer` is null on a real device (409).
template <int N>
void move_hand(HandPointerOf<N>* pointer, const std::string& request_body, LiveDocumentOf<N>& document,
               httplib::Response& res);

}  // namespace hapscene
