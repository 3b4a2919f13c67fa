// Foot slide: how fast feet move while they should be planted, and the largest jump of any
// joint between frames (DESIGN.md section 5b: every synthesized result is measured against the
// clips it was cut from; Kovar, Schreiner & Gleicher, SCA 2002, call the first footskate).
//
// From world positions in metres, y up, and foot contacts (motion/foot_contacts.h):
//  - contact speed: for each contact track measured (the toes; a foot without a toe joint by
//    its ankle; the ankles too with include_ankles) and each pair of consecutive frames f-1, f
//    both planted, the horizontal (xz) distance moved times fps, in m/s. A planted foot that
//    does not slide gives 0. Reported as the mean and the 95th percentile over all such steps.
//  - largest joint step: over all frames f >= 1 and joints, the distance a joint moves from
//    frame f-1 to f relative to the root (its position minus joint 0's), in metres; a pop in a
//    blend shows here, steady travel does not. Per frame, so compare at one frame rate. Also
//    the 99.9th percentile over frames of each frame's largest step: what a capture's rare
//    glitch (CMU 16_15's finger end jumps 0.92 m at its frame 1) does not set.
//
// The contacts the measure finds itself are by height alone (FootSlideSettings::contacts):
// planted while within 2 cm of the floor (the 2nd percentile of the toes' heights), whatever
// the speed. A speed threshold would leave out the very frames that slide. This is the measure
// used by hand so far (docs/performance.md). CMU subject 16's 15 clips at 30 fps: 0.088 m/s
// over all their planted steps pooled (as a walk's source clips are measured), 0.128 m/s as the
// mean of the clips' own means (the 0.130 of docs/performance.md); 16_15 alone 0.072.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/foot_contacts.h"

namespace mg {

// Contacts by height alone: within 2 cm of the clip's floor (not the local floor the database's
// contacts use), no speed limit, no gap filled, no shortest contact.
FootContactSettings foot_slide_contact_settings();

struct FootSlideSettings {
  FootJointNames joint_names;  // empty: found by name (skeleton/foot_joints.h)
  FootContactSettings contacts = foot_slide_contact_settings();
  bool include_ankles = false;  // measure the ankles' contacts as well as the toes'

  Status validate() const;
};

struct FootSlide {
  double mean_mps = 0.0;         // mean horizontal speed over planted steps (0 without any)
  double p95_mps = 0.0;          // its 95th percentile
  long long contact_steps = 0;   // planted steps measured
  double max_joint_step_m = 0.0; // largest per-frame joint step relative to the root
  double p999_joint_step_m = 0.0; // the 99.9th percentile of each frame's largest step
};

// The raw measurements, so that several motions (a walk's source clips) pool into one measure.
struct FootSlideSamples {
  std::vector<double> contact_speeds_mps;
  std::vector<double> frame_steps_m;  // per frame after the first, its largest joint step

  void add(const FootSlideSamples& other);
  FootSlide summary() const;
};

// Samples of positions (frames x joint_count, frame-major) with their contacts.
FootSlideSamples foot_slide_samples(std::span<const Vec3> world_positions_m, int joint_count, double fps,
                                    const FootContacts& contacts, bool include_ankles = false);

// A motion's samples: feet found, contacts detected with settings.contacts. Fails when the
// settings are wrong or the skeleton's feet cannot be found.
Result<FootSlideSamples> foot_slide_samples(const Skeleton& skeleton, const Motion& motion,
                                            const FootSlideSettings& settings = {});

// The measure of one motion.
Result<FootSlide> measure_foot_slide(const Skeleton& skeleton, const Motion& motion,
                                     const FootSlideSettings& settings = {});

}  // namespace mg
