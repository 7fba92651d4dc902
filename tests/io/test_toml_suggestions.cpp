// The "did you mean" of io/toml_reader: the optimal-string-alignment distance against
// hand-counted edits, and which candidates count as a misspelling.
#include <gtest/gtest.h>

#include "io/toml_reader.hpp"

using shudder::io::edit_distance;
using shudder::io::nearest_key;

TEST(TomlSuggestions, EditDistanceCountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(edit_distance("duration_s", "duration_s"), 0u);
  EXPECT_EQ(edit_distance("durration_s", "duration_s"), 1u);  // one insertion
  EXPECT_EQ(edit_distance("duratin_s", "duration_s"), 1u);    // one deletion
  EXPECT_EQ(edit_distance("duration_m", "duration_s"), 1u);   // one substitution
  EXPECT_EQ(edit_distance("duartion_s", "duration_s"), 1u);   // one adjacent swap (Levenshtein: 2)
  EXPECT_EQ(edit_distance("nu100_cSt", "nu40_cSt"), 2u);      // substitution + insertion
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // the textbook example
}

TEST(TomlSuggestions, NearestKeyOnlyForPlausibleMisspellings) {
  const std::vector<std::string> keys{"start_temp_C", "sump_start_temp_C", "fluid", "lining"};
  EXPECT_EQ(nearest_key("sump_strat_temp_C", keys), "sump_start_temp_C");
  EXPECT_EQ(nearest_key("strt_temp_C", keys), "start_temp_C");
  EXPECT_EQ(nearest_key("fluids", keys), "fluid");  // 6 chars: one edit allowed
  EXPECT_EQ(nearest_key("flood", keys), "");        // two edits on 5 chars: more than a third
  EXPECT_EQ(nearest_key("temperature", keys), "");
  EXPECT_EQ(nearest_key("ab", {"ac"}), "");  // 2 chars: no edit is "a third"
}
