// The exception side of the boundary (src/pg/boundary.hpp is PostgreSQL-free by design, so it
// is testable here; the SQLSTATE side is tested through SQL in tests/pgtap).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "pg/boundary.hpp"

using namespace streetgen;

// A throwing body must not make the call potentially-throwing: the entry points rely on it.
namespace {
auto throwing_body = [] { throw std::runtime_error("x"); };
}
static_assert(noexcept(pg::guarded_call(std::declval<pg::CallError&>(), throwing_body)), "guarded_call must be noexcept");

TEST(GuardedCall, NoExceptionLeavesNoError) {
  pg::CallError error;
  int ran = 0;
  pg::guarded_call(error, [&] { ran = 1; });
  EXPECT_EQ(ran, 1);
  EXPECT_FALSE(error.failed);
}

TEST(GuardedCall, CoreErrorKeepsKindMessageDetailHint) {
  pg::CallError error;
  pg::guarded_call(error, [] { throw core::Error(core::ErrorKind::bad_data, "msg", "detail.", "hint."); });
  ASSERT_TRUE(error.failed);
  EXPECT_EQ(error.kind, core::ErrorKind::bad_data);
  EXPECT_STREQ(error.message, "msg");
  EXPECT_STREQ(error.detail, "detail.");
  EXPECT_STREQ(error.hint, "hint.");
}

TEST(GuardedCall, StandardExceptionsMapToOutOfMemoryAndInternal) {
  pg::CallError error;
  pg::guarded_call(error, [] { throw std::bad_alloc(); });
  EXPECT_EQ(error.kind, core::ErrorKind::out_of_memory);
  pg::guarded_call(error, [] { throw std::logic_error("oops"); });
  EXPECT_EQ(error.kind, core::ErrorKind::internal);
  EXPECT_STREQ(error.detail, "oops");
  pg::guarded_call(error, [] { throw 42; });
  EXPECT_TRUE(error.failed);
  EXPECT_EQ(error.kind, core::ErrorKind::internal);
}

TEST(GuardedCall, LongMessagesAreTruncatedNotOverflowed) {
  pg::CallError error;
  std::string huge(10000, 'x');
  pg::guarded_call(error, [&] { throw core::Error(core::ErrorKind::invalid_argument, huge, huge, huge); });
  EXPECT_EQ(std::string(error.message).size(), sizeof(error.message) - 1);
  EXPECT_EQ(std::string(error.detail).size(), sizeof(error.detail) - 1);
}

