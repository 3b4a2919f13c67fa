// The names the studio answers to: a page of another site that rebinds its name to this
// machine is refused, the addresses and names a user opens it under are answered.
#include "studio/host_check.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mg::test {
namespace {

using studio::check_allowed_host;
using studio::host_allowed;
using studio::host_of_header;

TEST(HostCheck, ReadsTheHostOfAHeader) {
  EXPECT_EQ(host_of_header("localhost"), "localhost");
  EXPECT_EQ(host_of_header("LocalHost:8080"), "localhost");
  EXPECT_EQ(host_of_header("studio.lan.:80"), "studio.lan");
  EXPECT_EQ(host_of_header("127.0.0.1:65535"), "127.0.0.1");
  EXPECT_EQ(host_of_header("[::1]:8080"), "[::1]");
  EXPECT_EQ(host_of_header("[FE80::1]"), "[fe80::1]");
  for (const char* bad : {"", ":8080", "[::1", "[not-v6]:80", "[::1]x", "a b", "host:", "host:80x", "host:123456",
                          "user@host", "host/path", "."}) {
    EXPECT_EQ(host_of_header(bad), "") << bad;
  }
}

TEST(HostCheck, AnswersAddressesAndLocalhostOnly) {
  const std::vector<std::string> none;
  for (const char* ok : {"127.0.0.1:8080", "192.168.1.20", "[::1]:8080", "localhost:8080", "LOCALHOST",
                         "localhost.", "studio.localhost:1"}) {
    EXPECT_TRUE(host_allowed(ok, none)) << ok;
  }
  // Names a page of another site can rebind to this machine, and ones made to look like ours.
  for (const char* refused : {"evil.example:8080", "localhost.evil.example", "127.0.0.1.evil.example",
                              "evillocalhost", "127.0.0.1:80x", "", "[::1"}) {
    EXPECT_FALSE(host_allowed(refused, none)) << refused;
  }
}

TEST(HostCheck, AnswersTheNamesAllowed) {
  const std::vector<std::string> allowed = {"mybox", ".lan"};
  EXPECT_TRUE(host_allowed("mybox:8080", allowed));
  EXPECT_TRUE(host_allowed("MyBox", allowed));
  EXPECT_FALSE(host_allowed("mybox.example", allowed));
  EXPECT_FALSE(host_allowed("notmybox", allowed));
  EXPECT_TRUE(host_allowed("lan", allowed));
  EXPECT_TRUE(host_allowed("studio.lan:80", allowed));
  EXPECT_TRUE(host_allowed("a.b.lan", allowed));
  EXPECT_FALSE(host_allowed("evillan", allowed));
  EXPECT_FALSE(host_allowed("lan.evil", allowed));
}

TEST(HostCheck, AnAllowedHostIsANameAlone) {
  for (const char* ok : {"mybox", "studio.lan", ".lan", "my-box_2"}) {
    EXPECT_TRUE(check_allowed_host(ok)) << ok;
  }
  const auto message = [](const char* entry) {
    const Status checked = check_allowed_host(entry);
    return checked ? std::string() : checked.error().message;
  };
  EXPECT_NE(message("http://mybox:8080/").find("not a URL"), std::string::npos);
  EXPECT_NE(message("mybox:8080").find("without a port"), std::string::npos);
  EXPECT_NE(message("my box").find("not a host name"), std::string::npos);
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message(".").find("not a host name"), std::string::npos);
  for (const char* bad : {"-x", "x-", "..lan", "a..b", ".lan.", "a.-b"}) {
    EXPECT_NE(message(bad).find("not a host name"), std::string::npos) << bad;
  }
  for (const char* address : {"[::1]", "::1", "192.168.1.20"}) {
    EXPECT_NE(message(address).find("an IP address needs no --allow-host"), std::string::npos) << address;
  }
}

}  // namespace
}  // namespace mg::test
