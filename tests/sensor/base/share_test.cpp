// Tests for sensor/base/share: the shares of M partition the items (every item in exactly
// one share, listed in order), and parseShare's table of accepted and refused "k/M" texts,
// each refusal an InputError naming the key, the text and the range.
#include "sensor/base/share.h"

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

TEST(Share, SharesPartitionTheItems) {
  EXPECT_EQ(Share{}.count, 1);
  EXPECT_EQ(Share{}.itemsOf(7), 7);
  for (const int n : {0, 1, 5, 16, 37}) {
    for (const int m : {1, 2, 3, 7, n + 4}) {
      std::vector<int> owners(static_cast<std::size_t>(n), 0);
      for (int k = 0; k < m; ++k) {
        const Share share{k, m};
        int owned = 0;
        for (int t = 0; t < n; ++t) owned += share.owns(t) ? 1 : 0;
        ASSERT_EQ(share.itemsOf(n), owned) << k << " of " << m << ", " << n << " items";
        for (int i = 0; i < share.itemsOf(n); ++i) {
          const int t = share.item(i);
          ASSERT_TRUE(t >= 0 && t < n && share.owns(t)) << t;
          if (i > 0) {
            EXPECT_LT(share.item(i - 1), t);
          }
          ++owners[static_cast<std::size_t>(t)];
        }
      }
      for (const int o : owners) EXPECT_EQ(o, 1);
    }
  }
  // Items counted in std::size_t (a dataset's) are owned alike.
  EXPECT_TRUE((Share{2, 3}.owns(std::size_t{5})));
  EXPECT_FALSE((Share{2, 3}.owns(std::size_t{6})));
}

TEST(Share, ParseAcceptsKOfM) {
  struct Case {
    const char* text;
    int index, count;
  };
  for (const Case& c : {Case{"0/1", 0, 1}, Case{"1/2", 1, 2}, Case{"2/5", 2, 5},
                        Case{"007/8", 7, 8}, Case{"0/1048576", 0, kMaxShareCount},
                        Case{"1048575/1048576", kMaxShareCount - 1, kMaxShareCount}}) {
    const Share s = parseShare(c.text, "--tiles");
    EXPECT_EQ(s.index, c.index) << c.text;
    EXPECT_EQ(s.count, c.count) << c.text;
  }
}

TEST(Share, ParseRefusesAnythingElseNamingKeyTextAndRange) {
  for (const char* bad :
       {"2/2", "3/2", "-1/2", "-0/2", "+1/2", "1/0", "0/0", "1/-2", "a/2", "1/a", "1/", "/2", "/",
        "", "1", "12", "1/2/3", " 1/2", "1/2 ", "1 /2", "1/ 2", "1/2x", "0x1/2", "1.0/2", "1/2.0",
        "0/1048577", "0/4294967297", "99999999999999999999/2", "1/99999999999999999999",
        "18446744073709551617/18446744073709551618"}) {
    try {
      (void)parseShare(bad, "--shard");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "--shard");
      EXPECT_EQ(e.message(),
                std::string("expects k/M (share k of M, 0 <= k < M, 1 <= M <= 1048576), got '") +
                    bad + "'");
    }
  }
}

}  // namespace
}  // namespace camsim
