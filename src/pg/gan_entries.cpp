// StreetGAN sampling: generator file (bytea) in, PostGIS raster WKB out (sql/85-gan.sql turns it
// into a raster with ST_RastFromWKB); and the generator's metadata, which also validates a file
// before it is stored in streetgen.gan_generator.
#include <cstdint>
#include <vector>

#include "core/error.hpp"
#include "core/gan/generator.hpp"
#include "pg/array_args.hpp"
#include "pg/boundary.hpp"
#include "pg/owned_result.hpp"

extern "C" {
#include "catalog/pg_type.h"
}

using namespace streetgen;

namespace {

pg::ByteView blob_arg(FunctionCallInfo fcinfo, int n, const char* parameter) {
  if (PG_ARGISNULL(n)) pg::raise_null_argument(parameter);
  return pg::byte_view(PG_GETARG_DATUM(n));
}


}  // namespace

extern "C" {

PG_FUNCTION_INFO_V1(_streetgen_gan_sample);
// (generator bytea, width_px int4, height_px int4, seed int8, raw bool, upper_left_x float8,
//  upper_left_y float8, srid int4) -> bytea (PostGIS raster WKB)
Datum _streetgen_gan_sample(PG_FUNCTION_ARGS) {
  // Phase 1: arguments, every NULL named.
  pg::require_argument_count(fcinfo, 8, "_streetgen_gan_sample");
  const pg::ByteView generator = blob_arg(fcinfo, 0, "generator");
  const char* names[] = {"generator", "width_px", "height_px", "seed", "raw", "upper_left x", "upper_left y", "srid"};
  for (int a = 1; a < 8; ++a) {
    if (PG_ARGISNULL(a)) pg::raise_null_argument(names[a]);
  }
  const int width = PG_GETARG_INT32(1);
  const int height = PG_GETARG_INT32(2);
  const auto seed = static_cast<std::uint64_t>(PG_GETARG_INT64(3));
  const bool raw = PG_GETARG_BOOL(4);
  const double x0 = PG_GETARG_FLOAT8(5);
  const double y0 = PG_GETARG_FLOAT8(6);
  const std::int32_t srid = PG_GETARG_INT32(7);
  auto result = pg::OwnedResult<std::vector<std::uint8_t>>::create();

  // Phase 2: parse, sample, encode.
  pg::CallError error;
  pg::guarded_call(error, [&] {
    const core::gan::Generator g = core::gan::parse_generator(generator.data, generator.size);
    const core::gan::Image image = core::gan::sample(g, seed, width, height);
    result.emplace(core::gan::raster_wkb(image, raw, 0.0, x0, y0, g.metres_per_pixel, srid));
  });
  // Phase 3.
  pg::raise_if_failed(error);
  bytea* out = pg::to_bytea(*result);
  result.release();
  PG_RETURN_BYTEA_P(out);
}

PG_FUNCTION_INFO_V1(_streetgen_gan_generator_info);
// (weights bytea, OUT noise_channels int4, OUT layer_count int4, OUT parameter_count int8,
//  OUT metres_per_pixel float8, OUT kernel int4, OUT stride int4, OUT padding int4) -> record
Datum _streetgen_gan_generator_info(PG_FUNCTION_ARGS) {
  pg::require_argument_count(fcinfo, 1, "_streetgen_gan_generator_info");
  const pg::ByteView generator = blob_arg(fcinfo, 0, "weights");
  TupleDesc desc;
  if (get_call_result_type(fcinfo, nullptr, &desc) != TYPEFUNC_COMPOSITE || desc->natts != 7) {
    ereport(ERROR, (errcode(ERRCODE_FEATURE_NOT_SUPPORTED), errmsg("_streetgen_gan_generator_info: bad result type")));
  }
  struct Info {
    int noise_channels, layer_count, kernel, stride, padding;
    std::int64_t parameters;
    double metres_per_pixel;
  } info{};
  pg::CallError error;
  pg::guarded_call(error, [&] {
    const core::gan::Generator g = core::gan::parse_generator(generator.data, generator.size);
    info = {g.noise_channels, static_cast<int>(g.layers.size()), g.kernel, g.stride, g.padding,
            static_cast<std::int64_t>(g.parameter_count()), g.metres_per_pixel};
  });
  pg::raise_if_failed(error);
  Datum values[7] = {Int32GetDatum(info.noise_channels), Int32GetDatum(info.layer_count), Int64GetDatum(info.parameters),
                     Float8GetDatum(info.metres_per_pixel), Int32GetDatum(info.kernel), Int32GetDatum(info.stride),
                     Int32GetDatum(info.padding)};
  bool nulls[7] = {};
  desc = BlessTupleDesc(desc);
  PG_RETURN_DATUM(HeapTupleGetDatum(heap_form_tuple(desc, values, nulls)));
}

}  // extern "C"
