#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/ewkb.hpp"
#include "test_support.hpp"

using namespace streetgen;

TEST(Ewkb, RoundTripKeepsSridAndCoordinates) {
  core::GeosContext ctx;
  core::GeomPtr line = test::wkt(ctx, "LINESTRING(1.5 2.25, 10 20, -3 4)");
  core::Bytes bytes = core::write_ewkb(ctx, line.get(), 32631);
  // Little-endian marker, then the type word with the EWKB SRID flag (0x20000000) set.
  ASSERT_GT(bytes.size(), 9u);
  EXPECT_EQ(bytes[0], 1);
  EXPECT_EQ(bytes[4] & 0x20, 0x20);

  core::SridGeometry back = core::read_ewkb(ctx, bytes.data(), bytes.size(), "geom");
  EXPECT_EQ(back.srid, 32631);
  EXPECT_EQ(GEOSEqualsExact_r(ctx.handle(), back.geom.get(), line.get(), 0.0), 1);
}

TEST(Ewkb, SridZeroIsPlainWkb) {
  core::GeosContext ctx;
  core::GeomPtr point = test::wkt(ctx, "POINT(3 4)");
  core::Bytes bytes = core::write_ewkb(ctx, point.get(), 0);
  EXPECT_EQ(bytes.size(), 21u);  // 1 + 4 + 2 * 8: no SRID word
  EXPECT_EQ(core::read_ewkb(ctx, bytes.data(), bytes.size(), "geom").srid, 0);
}

TEST(Ewkb, GarbageIsBadDataNamingTheParameter) {
  core::GeosContext ctx;
  const std::uint8_t garbage[] = {0x01, 0x02, 0x00};
  try {
    core::read_ewkb(ctx, garbage, sizeof garbage, "axis");
    FAIL() << "garbage was accepted";
  } catch (const core::Error& e) {
    EXPECT_EQ(e.kind(), core::ErrorKind::bad_data);
    EXPECT_NE(std::string(e.what()).find("axis"), std::string::npos);
    EXPECT_FALSE(e.detail().empty());
  }
  // The context stays usable after a failure.
  core::GeomPtr ok = test::wkt(ctx, "POINT(1 1)");
  EXPECT_TRUE(ctx.last_error().empty());
}
