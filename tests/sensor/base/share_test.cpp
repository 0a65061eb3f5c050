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
  // Each refused text, with what is wrong with it.
  const char* const refused[][2] = {
      {"2/2", "k = M"},
      {"3/2", "k > M"},
      {"-1/2", "k < 0"},
      {"-0/2", "a sign"},
      {"+1/2", "a sign"},
      {"1/-2", "M < 0"},
      {"1/0", "M = 0"},
      {"0/0", "M = 0"},
      {"0/1048577", "M above 2^20"},
      {"0/4294967297", "M above 2^32"},
      {"99999999999999999999/2", "k beyond 64 bits"},
      {"1/99999999999999999999", "M beyond 64 bits"},
      {"18446744073709551617/18446744073709551618", "both beyond 64 bits"},
      {"a/2", "not a number"},
      {"1/a", "not a number"},
      {"0x1/2", "hexadecimal"},
      {"1.0/2", "a fraction"},
      {"1/2.0", "a fraction"},
      {"1/", "no M"},
      {"/2", "no k"},
      {"/", "neither"},
      {"", "empty"},
      {"1", "no slash"},
      {"12", "no slash"},
      {"1/2/3", "two slashes"},
      {" 1/2", "a leading blank"},
      {"1/2 ", "a trailing blank"},
      {"1 /2", "a blank before the slash"},
      {"1/ 2", "a blank after the slash"},
      {"1/2x", "trailing text"},
  };
  for (const auto& [bad, why] : refused) {
    try {
      (void)parseShare(bad, "--shard");
      ADD_FAILURE() << "accepted '" << bad << "' (" << why << ")";
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
