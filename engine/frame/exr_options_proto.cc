#include "frame/exr_options_proto.h"

#include "absl/strings/str_cat.h"

namespace aperture {

absl::StatusOr<ExrOptions> ExrOptionsFromProto(const v1::RenderOptions& options) {
  ExrOptions exr;
  switch (options.pixel_type()) {
    case v1::PIXEL_TYPE_DEFAULT:
    case v1::PIXEL_TYPE_HALF:
      exr.pixel_type = ExrPixelType::kHalf;
      break;
    case v1::PIXEL_TYPE_FLOAT:
      exr.pixel_type = ExrPixelType::kFloat;
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("options.pixel_type has unknown value ", options.pixel_type()));
  }
  switch (options.compression()) {
    case v1::EXR_COMPRESSION_DEFAULT:
    case v1::EXR_COMPRESSION_ZIP:
      exr.compression = ExrCompression::kZip;
      break;
    case v1::EXR_COMPRESSION_NONE:
      exr.compression = ExrCompression::kNone;
      break;
    case v1::EXR_COMPRESSION_RLE:
      exr.compression = ExrCompression::kRle;
      break;
    case v1::EXR_COMPRESSION_ZIPS:
      exr.compression = ExrCompression::kZips;
      break;
    case v1::EXR_COMPRESSION_PIZ:
      exr.compression = ExrCompression::kPiz;
      break;
    case v1::EXR_COMPRESSION_DWAA:
      exr.compression = ExrCompression::kDwaa;
      break;
    case v1::EXR_COMPRESSION_B44:
      exr.compression = ExrCompression::kB44;
      break;
    case v1::EXR_COMPRESSION_B44A:
      exr.compression = ExrCompression::kB44a;
      break;
    case v1::EXR_COMPRESSION_DWAB:
      exr.compression = ExrCompression::kDwab;
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("options.compression has unknown value ", options.compression()));
  }
  // No silent fallback to half: the caller asked for float values and would get other numbers.
  if (CompressesHalfOnly(exr.compression) && exr.pixel_type == ExrPixelType::kFloat)
    return absl::InvalidArgumentError(
        absl::StrCat("options.pixel_type FLOAT (--float-pixels) with options.compression ",
                     ExrCompressionName(exr.compression), ": ", ExrCompressionName(exr.compression),
                     " compresses half channels only; ask for half pixels or another compression"));
  return exr;
}

}  // namespace aperture
