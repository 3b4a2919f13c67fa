// Which length unit a file without one (BVH) is in, from the size of its figure: the unit
// among metres, centimetres, millimetres, inches and CMU's ASF unit (1/0.45 inch, CMU's BVH
// conversions keep it) that gives the figure the most plausible human size.
//
// The size is measured on the animation, not the rest pose (some files' OFFSETs are zero when
// channels carry the positions): per frame, the largest of the figure's x, y and z extents over
// all its joints (standing: head to toe; T-pose: about the arm span; lying: head to toe along
// the floor), and the median of that over the frames. A size fits a unit when it gives
// kPlausibleHeightMinM..kPlausibleHeightMaxM; among the units that fit, the one closest to
// kTypicalHeightM (by ratio) wins. When none fits, the file is read in metres and `plausible`
// is false so that the caller can warn.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/motion/length_unit_choice.h"
#include "motiongraph/motion/motion.h"

namespace mg {

// The candidates, in the order above.
std::span<const LengthUnit> length_unit_candidates();

constexpr double kTypicalHeightM = 1.7;
constexpr double kPlausibleHeightMinM = 0.9;
constexpr double kPlausibleHeightMaxM = 2.6;

// The figure's size in the units of its skeleton and motion (see above); without frames, its
// rest pose's (a BVH of a skeleton alone).
double figure_size(const Skeleton& skeleton, const Motion& motion);
// The same from world positions already computed: frames x joint_count, frame-major.
double figure_size(std::span<const Vec3> world_positions, int joint_count);
// Per frame, the figure's extent along x, y and z over all its joints (+infinity where huge
// values overflow), in the same units: what figure_size and the up axis (up_axis.h) measure.
std::vector<Vec3> frame_extents(const Skeleton& skeleton, const Motion& motion);
// The median (the upper one of an even count); 0 when empty.
double median_of(std::vector<double> values);

// The unit for a figure of that size.
LengthUnitChoice choose_length_unit(double figure_size_units);

// Multiplies every length of a clip (offsets, translations, static ancestors) by `factor`.
void scale_lengths(Clip& clip, double factor);

}  // namespace mg
