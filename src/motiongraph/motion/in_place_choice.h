// Where a clip's travel over the floor came from, and what it was decided on: see in_place.h.
#pragma once

namespace mg {

// Where each clip's travel comes from: the root as read, the planted feet, or the feet for
// clips animated in place and the root otherwise.
enum class TravelSource { kAuto, kRoot, kFeet };

struct InPlaceChoice {
  double slide_speed_m_s = 0.0;  // median speed of the stillest foot joint on the floor
  double root_speed_m_s = 0.0;   // the root's own speed over the floor
  double ground_share = 0.0;     // share of the clip's frame intervals with a foot on the floor
  bool in_place = false;         // judged animated in place
  bool recovered = false;        // the travel was recovered from the feet
  double recovered_m = 0.0;      // the travel added, metres (its path sampled every half second)
};

}  // namespace mg
