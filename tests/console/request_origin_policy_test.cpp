// The console's Host and Origin rules against the attacks they stop: a page of another site
// (cross-site POST, WebSocket), a name that resolves to us (DNS rebinding), a sandboxed page's
// "null" origin, and headers that are no host at all; and against what must still work: the
// console's own page, curl and Prometheus (no Origin), IPv6 literals, ports, names in any case.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "server/console/request_origin_policy.hpp"

namespace netmc::console {
namespace {

using std::nullopt;

TEST(RequestOriginPolicy, LoopbackNamesAndTheBindAddressAreTheConsolesOwn) {
  const auto policy = RequestOriginPolicy::loopback_and("10.7.0.2", {});
  for (const char* host : {"localhost", "LocalHost:7380", "127.0.0.1", "127.0.0.1:7380", "[::1]", "[::1]:7380",
                           "10.7.0.2:7380"}) {
    EXPECT_EQ(policy.refusal(host, nullopt), nullopt) << host;
  }
  EXPECT_EQ(policy.refusal("127.0.0.1:7380", "http://127.0.0.1:7380"), nullopt);
  EXPECT_EQ(policy.refusal("localhost:7380", "https://localhost:7380"), nullopt);
  EXPECT_EQ(policy.refusal("[::1]:7380", "http://[::1]:7380"), nullopt);
}

TEST(RequestOriginPolicy, AnyAddressBindsNoNameButLoopbackAndTheAllowedOnes) {
  const auto policy = RequestOriginPolicy::loopback_and("0.0.0.0", {"lab-pc.example", "server"});
  EXPECT_EQ(policy.refusal("server:7380", nullopt), nullopt);  // Prometheus in docker/compose.yaml
  EXPECT_EQ(policy.refusal("LAB-PC.example", "http://lab-pc.example:7380"), nullopt);
  const auto refused = policy.refusal("0.0.0.0:7380", nullopt);
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->find("--http-allow-host 0.0.0.0"), std::string::npos) << *refused;
  EXPECT_EQ(policy.describe(), "localhost, 127.0.0.1, ::1, lab-pc.example, server");
}

TEST(RequestOriginPolicy, ACrossSitePageIsRefusedNamingItsOrigin) {
  const auto policy = RequestOriginPolicy::loopback_and("127.0.0.1", {});
  const auto refused = policy.refusal("127.0.0.1:7380", "http://evil.example");
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->find("Origin 'http://evil.example'"), std::string::npos) << *refused;
  // The same host under another scheme is still a page of ours; anything else is not.
  for (const char* origin : {"null", "evil.example", "file://", "http://127.0.0.1.evil.example",
                             "http://127.0.0.1:7380/path", "ftp://127.0.0.1", "http://", "http://user@127.0.0.1"}) {
    EXPECT_TRUE(policy.refusal("127.0.0.1:7380", origin)) << origin;
  }
}

TEST(RequestOriginPolicy, AForeignHostIsRefusedEvenWithoutOrigin) {
  const auto policy = RequestOriginPolicy::loopback_and("127.0.0.1", {});
  const auto rebinding = policy.refusal("evil.example:7380", nullopt);  // DNS rebinding: our address, their name
  ASSERT_TRUE(rebinding);
  EXPECT_NE(rebinding->find("Host 'evil.example'"), std::string::npos) << *rebinding;
  EXPECT_TRUE(policy.refusal(nullopt, nullopt));  // HTTP/1.1 needs one
  for (const char* host : {"", ":7380", "127.0.0.1:", "127.0.0.1:99999x", "[::1", "a b", "a/b", "[::1]x",
                           "127.0.0.1:7380:1", "evil\"}{", "[zz]"}) {
    EXPECT_TRUE(policy.refusal(host, nullopt)) << host;
  }
}

TEST(RequestOriginPolicy, AMessageShowsNoHeaderAsSentButAPrintableBoundedQuote) {
  const auto policy = RequestOriginPolicy::loopback_and("127.0.0.1", {});
  const std::string hostile = "http://x\"}\n\\" + std::string(300, 'a');
  const auto refused = policy.refusal("127.0.0.1", hostile);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->find('"'), std::string::npos) << *refused;  // it goes into a JSON string
  EXPECT_EQ(refused->find('\\'), std::string::npos) << *refused;
  EXPECT_EQ(refused->find('\n'), std::string::npos) << *refused;
  EXPECT_LT(refused->size(), 200u);
}

TEST(RequestOriginPolicy, AStarAllowsAnyHostAndOrigin) {
  const RequestOriginPolicy policy({"*"});
  EXPECT_EQ(policy.refusal("evil.example", "http://evil.example"), nullopt);
  EXPECT_EQ(policy.describe(), "any host");
}

}  // namespace
}  // namespace netmc::console
