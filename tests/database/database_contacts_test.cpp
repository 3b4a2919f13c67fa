#include "motiongraph/database/database_contacts.h"

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

TEST(DatabaseContacts, EachFrameHasItsClipsContacts) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc"});
  auto masks = database_contacts(db);
  ASSERT_TRUE(masks) << masks.error().to_string();
  ASSERT_EQ(static_cast<int>(masks->size()), db.frame_count());
  int planted = 0;
  for (const DatabaseClip& clip : db.clips) {
    const Skeleton& skeleton = db.skeletons[clip.skeleton];
    const FootJoints feet = *find_foot_joints(skeleton);
    const FootContacts contacts = *detect_foot_contacts(skeleton, clip.motion, feet, {});
    for (int f = 0; f < clip.frame_count; ++f) {
      ContactMask expected = 0;
      for (const FootContactTrack& track : contacts.tracks) {
        if (track.planted[f]) expected |= contact_bit(track.side, track.part);
      }
      ASSERT_EQ((*masks)[clip.first_frame + f], expected) << clip.name << " frame " << f;
      planted += expected != 0 ? 1 : 0;
    }
  }
  EXPECT_GT(planted, db.frame_count() / 2);  // walking and running: a foot down most of the time
}

TEST(DatabaseContacts, NamesTheSkeletonWhoseFeetAreMissing) {
  const MotionDatabase db = test::small_database({"cmu/16/16_15.amc"});
  FootJointNames names;
  names.left_ankle = "no_such_joint";
  auto masks = database_contacts(db, {}, names);
  ASSERT_FALSE(masks);
  const std::string name = db.skeleton_names.empty() ? "skeleton '0'" : "skeleton '" + db.skeleton_names[0] + "'";
  EXPECT_NE(masks.error().message.find(name), std::string::npos) << masks.error().message;
  EXPECT_NE(masks.error().message.find("no_such_joint"), std::string::npos) << masks.error().message;
}

}  // namespace
}  // namespace mg
