#pragma once
// Internal to render/video: FFmpeg's libraries (libavutil, libavcodec, libavformat, libavfilter),
// opened when a video is first written or read rather than linked. With their closure of some 170
// libraries (x264, libvpx, and libavfilter's own) they cost every start of the program about ten
// times what the rest of it does, though most commands write no video (bench/README.md, "scripts/test
// on a new machine"). Opened once for the process and never closed; the functions are those of
// FFmpeg's headers, by their declared types, called as `libav::ffmpeg().avcodec_open2(…)`.

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavfilter/avfilter.h>
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/log.h>
#include <libavutil/mathematics.h>
#include <libavutil/opt.h>
}

namespace particles::render::libav {

// Every libav function the program calls, each with the library that defines it. One more call is
// one more row here.
#define PARTICLES_LIBAV_FUNCTIONS(X)          \
  X(avutil, av_dict_count)                    \
  X(avutil, av_dict_free)                     \
  X(avutil, av_dict_get)                      \
  X(avutil, av_dict_set)                      \
  X(avutil, av_frame_alloc)                   \
  X(avutil, av_frame_clone)                   \
  X(avutil, av_frame_free)                    \
  X(avutil, av_frame_get_buffer)              \
  X(avutil, av_frame_make_writable)           \
  X(avutil, av_frame_unref)                   \
  X(avutil, av_log_set_level)                 \
  X(avutil, av_opt_set)                       \
  X(avutil, av_rescale_q_rnd)                 \
  X(avutil, av_rescale_rnd)                   \
  X(avutil, av_strerror)                      \
  X(avcodec, av_packet_alloc)                 \
  X(avcodec, av_packet_free)                  \
  X(avcodec, av_packet_rescale_ts)            \
  X(avcodec, av_packet_unref)                 \
  X(avcodec, avcodec_alloc_context3)          \
  X(avcodec, avcodec_find_decoder)            \
  X(avcodec, avcodec_find_encoder_by_name)    \
  X(avcodec, avcodec_free_context)            \
  X(avcodec, avcodec_get_name)                \
  X(avcodec, avcodec_open2)                   \
  X(avcodec, avcodec_parameters_alloc)        \
  X(avcodec, avcodec_parameters_copy)         \
  X(avcodec, avcodec_parameters_free)         \
  X(avcodec, avcodec_parameters_from_context) \
  X(avcodec, avcodec_parameters_to_context)   \
  X(avcodec, avcodec_receive_frame)           \
  X(avcodec, avcodec_receive_packet)          \
  X(avcodec, avcodec_send_frame)              \
  X(avcodec, avcodec_send_packet)             \
  X(avformat, av_interleaved_write_frame)     \
  X(avformat, av_read_frame)                  \
  X(avformat, av_write_trailer)               \
  X(avformat, avformat_alloc_output_context2) \
  X(avformat, avformat_close_input)           \
  X(avformat, avformat_find_stream_info)      \
  X(avformat, avformat_free_context)          \
  X(avformat, avformat_new_stream)            \
  X(avformat, avformat_open_input)            \
  X(avformat, avformat_write_header)          \
  X(avformat, avio_closep)                    \
  X(avformat, avio_open2)                     \
  X(avfilter, av_buffersink_get_frame)        \
  X(avfilter, av_buffersink_get_time_base)    \
  X(avfilter, av_buffersrc_add_frame_flags)   \
  X(avfilter, avfilter_get_by_name)           \
  X(avfilter, avfilter_graph_alloc)           \
  X(avfilter, avfilter_graph_config)          \
  X(avfilter, avfilter_graph_create_filter)   \
  X(avfilter, avfilter_graph_free)            \
  X(avfilter, avfilter_link)

// The functions, each a pointer of its declared type.
struct Functions {
#define PARTICLES_LIBAV_POINTER(library, name) decltype(&::name) name = nullptr;
  PARTICLES_LIBAV_FUNCTIONS(PARTICLES_LIBAV_POINTER)
#undef PARTICLES_LIBAV_POINTER
};

// The functions, the libraries opened on the first call (thread-safe). Throws OutputError naming
// the library and what to install when one cannot be opened or lacks a function.
const Functions& ffmpeg();

// libav's log level (AV_LOG_ERROR, AV_LOG_INFO), set now if the libraries are open, else when they
// are opened: choosing how much libav prints does not open them.
void setLogLevel(int level);

}  // namespace particles::render::libav
