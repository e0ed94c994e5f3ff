// Event names are a fixed contract: every type has a name, and the name parses back to the type.
#include <gtest/gtest.h>

#include <set>

#include "raystep/record/events.h"

namespace raystep {
namespace {

TEST(Events, NamesRoundTripAndAreUnique) {
  std::set<std::string> names;
  for (int i = 0; i < kEventTypeCount; ++i) {
    std::string name = event_type_name(EventType(i));
    EventType back;
    ASSERT_TRUE(parse_event_type(name, &back)) << name;
    EXPECT_EQ(int(back), i);
    names.insert(name);
  }
  EXPECT_EQ(names.size(), size_t(kEventTypeCount));
  EventType t;
  EXPECT_FALSE(parse_event_type("teleport", &t));
  // The names the trace format documents.
  EXPECT_STREQ(event_type_name(EventType::mailbox_hit), "mailbox_hit");
  EXPECT_STREQ(event_type_name(EventType::hit_deferred), "hit_deferred");
  EXPECT_STREQ(event_type_name(EventType::sah_candidate), "sah_candidate");
  EXPECT_STREQ(event_type_name(EventType::box_test), "box_test");  // version 3
  EXPECT_STREQ(event_type_name(EventType::skip), "skip");
}

TEST(Events, AcceptReasonsRoundTrip) {
  for (AcceptReason r : {AcceptReason::inside_cell, AcceptReason::any_hit, AcceptReason::structure_done}) {
    AcceptReason back;
    ASSERT_TRUE(parse_accept_reason(accept_reason_name(r), &back));
    EXPECT_EQ(back, r);
  }
}

}  // namespace
}  // namespace raystep
