#include "io/exr_chunk_encoder.h"

#include <OpenEXR/openexr.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <vector>

#include "absl/strings/str_cat.h"
#include "io/exr_deflate.h"
#include "io/exr_pack.h"

namespace aperture {
namespace {

// Where the core library's writes land (offsets into one growing string) and its first error.
struct Sink {
  std::string* bytes = nullptr;
  std::mutex mutex;
  std::string error;
};

int64_t WriteToSink(exr_const_context_t, void* user_data, const void* buffer, uint64_t size,
                    uint64_t offset, exr_stream_error_func_ptr_t) {
  std::string& bytes = *static_cast<Sink*>(user_data)->bytes;
  // The chunks come in file order, at the end: appended, one pass over the frame's bytes (a
  // resize would zero them first). The header's offset table is written again in place.
  if (offset == bytes.size()) {
    bytes.append(static_cast<const char*>(buffer), size);
    return static_cast<int64_t>(size);
  }
  if (bytes.size() < offset + size) bytes.resize(offset + size);
  std::memcpy(bytes.data() + offset, buffer, size);
  return static_cast<int64_t>(size);
}

void KeepFirstError(exr_const_context_t context, exr_result_t code, const char* message) {
  void* user_data = nullptr;
  if (exr_get_user_data(context, &user_data) != EXR_ERR_SUCCESS || user_data == nullptr) return;
  Sink& sink = *static_cast<Sink*>(user_data);
  std::lock_guard lock(sink.mutex);
  if (sink.error.empty())
    sink.error = absl::StrCat(message != nullptr ? message : "", " (",
                              exr_get_error_code_as_string(code), ")");
}

exr_compression_t CoreCompression(ExrCompression c) {
  switch (c) {
    case ExrCompression::kNone:
      return EXR_COMPRESSION_NONE;
    case ExrCompression::kRle:
      return EXR_COMPRESSION_RLE;
    case ExrCompression::kZips:
      return EXR_COMPRESSION_ZIPS;
    case ExrCompression::kZip:
      return EXR_COMPRESSION_ZIP;
    case ExrCompression::kPiz:
      return EXR_COMPRESSION_PIZ;
    case ExrCompression::kDwaa:
      return EXR_COMPRESSION_DWAA;
    case ExrCompression::kB44:
      return EXR_COMPRESSION_B44;
    case ExrCompression::kB44a:
      return EXR_COMPRESSION_B44A;
    case ExrCompression::kDwab:
      return EXR_COMPRESSION_DWAB;
  }
  return EXR_COMPRESSION_ZIP;
}

// A run of consecutive chunks encoded by one task: about 32 scanlines, so that the one-line
// chunks of none, rle and zips do not each pay a task.
struct Batch {
  int first_chunk = 0;
  int chunks = 0;
  std::string bytes;            // the chunks' compressed bytes, back to back
  std::vector<uint64_t> sizes;  // each chunk's share of `bytes`
  exr_result_t result = EXR_ERR_SUCCESS;
};

// The context for one image being written; owns the core library's context.
class ChunkWriter {
 public:
  ChunkWriter(const Image& image, const ExrOptions& options, Sink& sink)
      : image_(image),
        half_(options.pixel_type == ExrPixelType::kHalf),
        deflate_(options.compression == ExrCompression::kZip ||
                 options.compression == ExrCompression::kZips),
        zip_level_(options.zip_level),
        y0_(options.metadata.y),
        sink_(sink) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &sink_;
    init.write_fn = &WriteToSink;
    init.error_handler_fn = &KeepFirstError;
    init.zip_level = options.zip_level;
    result_ = exr_start_write(&context_, "frame.exr", EXR_WRITE_FILE_DIRECTLY, &init);
    if (result_ == EXR_ERR_SUCCESS) result_ = WriteHeader(options);
  }
  ~ChunkWriter() {
    if (context_ != nullptr) exr_finish(&context_);
  }
  ChunkWriter(const ChunkWriter&) = delete;
  ChunkWriter& operator=(const ChunkWriter&) = delete;

  exr_result_t WriteChunks() {
    if (result_ != EXR_ERR_SUCCESS) return result_;
    const int lines = lines_per_chunk_;
    const int chunks = (image_.height() + lines - 1) / lines;
    const int per_batch = std::max(1, 32 / lines);
    std::vector<Batch> batches((chunks + per_batch - 1) / per_batch);
    for (size_t b = 0; b < batches.size(); ++b) {
      batches[b].first_chunk = static_cast<int>(b) * per_batch;
      batches[b].chunks = std::min(per_batch, chunks - batches[b].first_chunk);
    }
    // Compression in parallel, writes in file order (the core library requires increasing y);
    // the tokens bound how many compressed batches wait for the writer.
    size_t next = 0;
    const size_t tokens = 2 * static_cast<size_t>(tbb::this_task_arena::max_concurrency());
    tbb::parallel_pipeline(
        tokens, tbb::make_filter<void, Batch*>(tbb::filter_mode::serial_in_order,
                                               [&](tbb::flow_control& flow) -> Batch* {
                                                 if (next == batches.size()) {
                                                   flow.stop();
                                                   return nullptr;
                                                 }
                                                 return &batches[next++];
                                               }) &
                    tbb::make_filter<Batch*, Batch*>(tbb::filter_mode::parallel,
                                                     [&](Batch* batch) {
                                                       Compress(*batch);
                                                       return batch;
                                                     }) &
                    tbb::make_filter<Batch*, void>(tbb::filter_mode::serial_in_order,
                                                   [&](Batch* batch) { Write(*batch); }));
    if (result_ != EXR_ERR_SUCCESS) return result_;
    result_ = exr_finish(&context_);
    context_ = nullptr;
    return result_;
  }

 private:
  exr_result_t WriteHeader(const ExrOptions& options) {
    exr_result_t r = exr_add_part(context_, "", EXR_STORAGE_SCANLINE, &part_);
    // The data window is where the image lies in its frame, the display window the whole frame.
    const ExrMetadata& m = options.metadata;
    exr_attr_box2i_t data, display;
    data.min.x = m.x;
    data.min.y = y0_;
    data.max.x = m.x + image_.width() - 1;
    data.max.y = y0_ + image_.height() - 1;
    display = data;
    if (m.frame_width > 0) {
      display.min.x = display.min.y = 0;
      display.max.x = m.frame_width - 1;
      display.max.y = m.frame_height - 1;
    }
    exr_attr_v2f_t centre;
    centre.x = centre.y = 0.0f;
    if (r == EXR_ERR_SUCCESS)
      r = exr_initialize_required_attr(context_, part_, &display, &data, 1.0f, &centre, 1.0f,
                                       EXR_LINEORDER_INCREASING_Y,
                                       CoreCompression(options.compression));
    if (r == EXR_ERR_SUCCESS) r = exr_set_zip_compression_level(context_, part_, options.zip_level);
    const exr_pixel_type_t type = half_ ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    for (const char* name : {"R", "G", "B", "A"})
      if (r == EXR_ERR_SUCCESS)
        r = exr_add_channel(context_, part_, name, type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    for (const ExrAttribute& a : HeaderAttributes(m)) {
      if (r != EXR_ERR_SUCCESS) break;
      r = a.is_number ? exr_attr_set_float(context_, part_, a.name.c_str(), a.number)
                      : exr_attr_set_string(context_, part_, a.name.c_str(), a.text.c_str());
    }
    if (r == EXR_ERR_SUCCESS) r = exr_write_header(context_);
    if (r == EXR_ERR_SUCCESS) r = exr_get_scanlines_per_chunk(context_, part_, &lines_per_chunk_);
    return r;
  }

  // Packs (float to half where asked) and compresses the batch's chunks into batch.bytes.
  void Compress(Batch& batch) const {
    exr_encode_pipeline_t encode = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool initialized = false;
    batch.sizes.reserve(batch.chunks);
    for (int i = 0; i < batch.chunks && batch.result == EXR_ERR_SUCCESS; ++i) {
      const int y = (batch.first_chunk + i) * lines_per_chunk_;
      exr_chunk_info_t chunk;
      exr_result_t r = exr_write_scanline_chunk_info(context_, part_, y0_ + y, &chunk);
      if (r == EXR_ERR_SUCCESS)
        r = initialized ? exr_encoding_update(context_, part_, &chunk, &encode)
                        : exr_encoding_initialize(context_, part_, &chunk, &encode);
      if (r == EXR_ERR_SUCCESS) {
        PointAtRows(encode, y);
        if (!initialized) r = exr_encoding_choose_default_routines(context_, part_, &encode);
        if (!initialized) {
          if (ExrPackFn pack = FastRgbaPack()) encode.convert_and_pack_fn = pack;
        }
        if (!initialized && deflate_) {
          encode.compress_fn = &DeflateExrChunk;
          encode.encoding_user_data = const_cast<int*>(&zip_level_);
        }
        initialized = true;
      }
      // The writes happen in order in the pipeline's last stage, not here.
      encode.yield_until_ready_fn = nullptr;
      encode.write_fn = nullptr;
      if (r == EXR_ERR_SUCCESS) r = exr_encoding_run(context_, part_, &encode);
      if (r == EXR_ERR_SUCCESS) {
        batch.bytes.append(static_cast<const char*>(encode.compressed_buffer),
                           encode.compressed_bytes);
        batch.sizes.push_back(encode.compressed_bytes);
      }
      batch.result = r;
    }
    if (initialized) exr_encoding_destroy(context_, &encode);
  }

  // The channels read straight from the interleaved float frame; the core's packing converts
  // to half (round to nearest even, as Imath::half does).
  void PointAtRows(exr_encode_pipeline_t& encode, int y) const {
    const Rgba* row = image_.texels().data() + static_cast<size_t>(y) * image_.width();
    for (int c = 0; c < encode.channel_count; ++c) {
      exr_coding_channel_info_t& channel = encode.channels[c];
      const int offset = std::string_view("RGBA").find(channel.channel_name[0]);
      channel.user_bytes_per_element = sizeof(float);
      channel.user_data_type = EXR_PIXEL_FLOAT;
      channel.user_pixel_stride = sizeof(Rgba);
      channel.user_line_stride = static_cast<int32_t>(sizeof(Rgba) * image_.width());
      channel.encode_from_ptr = reinterpret_cast<const uint8_t*>(&row->r + offset);
    }
  }

  void Write(Batch& batch) {
    if (result_ == EXR_ERR_SUCCESS) result_ = batch.result;
    size_t at = 0;
    for (int i = 0; i < batch.chunks && result_ == EXR_ERR_SUCCESS; ++i) {
      const int y = (batch.first_chunk + i) * lines_per_chunk_;
      result_ = exr_write_scanline_chunk(context_, part_, y0_ + y, batch.bytes.data() + at,
                                         batch.sizes[i]);
      at += batch.sizes[i];
    }
    std::string().swap(batch.bytes);  // written: free it now, not when the frame is done
  }

  const Image& image_;
  const bool half_;
  const bool deflate_;  // zip and zips by libdeflate (io/exr_deflate.h)
  const int zip_level_;
  const int y0_;  // the data window's first row: chunks are addressed in frame rows
  Sink& sink_;
  exr_context_t context_ = nullptr;
  int part_ = 0;
  int lines_per_chunk_ = 1;
  exr_result_t result_ = EXR_ERR_SUCCESS;
};

}  // namespace

bool CoreEncoderSupports(ExrCompression compression) {
  return compression != ExrCompression::kDwaa && compression != ExrCompression::kDwab;
}

absl::Status EncodeExrChunks(const Image& image, const ExrOptions& options, std::string* bytes) {
  if (!CoreEncoderSupports(options.compression))
    return absl::InvalidArgumentError(absl::StrCat("OpenEXR's core library cannot write ",
                                                   ExrCompressionName(options.compression)));
  if (image.empty()) return absl::InvalidArgumentError("cannot encode an empty image");
  bytes->clear();
  // The whole frame uncompressed plus the header and offset table: no reallocation for `none`.
  const size_t channel_bytes = options.pixel_type == ExrPixelType::kHalf ? 2 : 4;
  bytes->reserve(4 * channel_bytes * image.texels().size() + 16 * image.height() + 4096);
  Sink sink;
  sink.bytes = bytes;
  exr_result_t result;
  auto encode = [&] {
    ChunkWriter writer(image, options, sink);
    result = writer.WriteChunks();
  };
  if (options.threads > 0)
    tbb::task_arena(options.threads).execute(encode);
  else
    encode();
  if (result != EXR_ERR_SUCCESS)
    return absl::InternalError(
        absl::StrCat("EXR encoding failed: ",
                     sink.error.empty() ? exr_get_default_error_message(result) : sink.error));
  return absl::OkStatus();
}

}  // namespace aperture
