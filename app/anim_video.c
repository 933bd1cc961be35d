/* Films through FFmpeg: libavformat picks the container from the file name, its default video
 * encoder (H.264 by libx264 for .mp4/.mkv/.mov, VP9 by libvpx for .webm) runs in constant-quality
 * mode, libswscale turns our sRGB RGBA rows into the encoder's YUV 4:2:0 (BT.601, limited range,
 * the players' default for untagged SD-size video; tagged so players need not guess).
 * Built as the module libcasteljau_video.so (anim_video_plugin.h), opened only by a film. */
#include "anim_video.h"
#include "anim_video_plugin.h"

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

struct anim_video {
    AVFormatContext *fmt;
    AVCodecContext *enc;
    AVStream *stream;
    struct SwsContext *sws;
    AVFrame *frame;
    AVPacket *pkt;
    int64_t next_pts;
    int header_written;
};

static void av_reason(char *why, int size, const char *what, int err) {
    char msg[AV_ERROR_MAX_STRING_SIZE];
    av_strerror(err, msg, sizeof msg);
    snprintf(why, (size_t)size, "%s (%s)", what, msg);
}

static void free_all(anim_video *v) {
    if (v->fmt && !(v->fmt->oformat->flags & AVFMT_NOFILE) && v->fmt->pb) avio_closep(&v->fmt->pb);
    avformat_free_context(v->fmt);
    avcodec_free_context(&v->enc);
    sws_freeContext(v->sws);
    av_frame_free(&v->frame);
    av_packet_free(&v->pkt);
    free(v);
}

/* Sets the encoder's constant quality: its CRF where it has one, else a fixed quantiser. */
static void set_quality(AVCodecContext *enc, const AVCodec *codec, int quality) {
    const double q = (100.0 - quality) / 99.0; /* 0 best .. 1 smallest */
    if (codec->id == AV_CODEC_ID_H264 || codec->id == AV_CODEC_ID_HEVC) {
        av_opt_set_double(enc->priv_data, "crf", round(51.0 * q), 0);
    } else if (codec->id == AV_CODEC_ID_VP9 || codec->id == AV_CODEC_ID_VP8 ||
               codec->id == AV_CODEC_ID_AV1) {
        av_opt_set_int(enc->priv_data, "crf", (int64_t)round(63.0 * q), 0);
        enc->bit_rate = 0;                                /* constant quality, no bitrate target */
        av_opt_set_int(enc->priv_data, "cpu-used", 5, 0); /* libvpx: fast, still good */
        av_opt_set(enc->priv_data, "deadline", "good", 0);
    } else {
        enc->flags |= AV_CODEC_FLAG_QSCALE;
        enc->global_quality = (int)(FF_QP2LAMBDA * (1.0 + 30.0 * q));
    }
}

anim_video *anim_video_open(const char *path, int width, int height, double fps, int quality,
                            char *why, int why_size) {
    if (width % 2 || height % 2) {
        snprintf(why, (size_t)why_size,
                 "a film needs an even width and height (4:2:0 colour); got %d x %d", width,
                 height);
        return NULL;
    }
    anim_video *v = calloc(1, sizeof *v);
    if (!v) {
        snprintf(why, (size_t)why_size, "out of memory");
        return NULL;
    }
    av_log_set_level(AV_LOG_ERROR); /* the encoders' statistics are not our output */
    int err = avformat_alloc_output_context2(&v->fmt, NULL, NULL, path);
    if (err < 0 || !v->fmt) {
        av_reason(why, why_size, "no container for this file name", err);
        free_all(v);
        return NULL;
    }
    const AVCodec *codec = avcodec_find_encoder(v->fmt->oformat->video_codec);
    if (!codec) {
        snprintf(why, (size_t)why_size, "this FFmpeg has no %s encoder for %s",
                 avcodec_get_name(v->fmt->oformat->video_codec), v->fmt->oformat->name);
        free_all(v);
        return NULL;
    }
    v->stream = avformat_new_stream(v->fmt, NULL);
    v->enc = avcodec_alloc_context3(codec);
    v->frame = av_frame_alloc();
    v->pkt = av_packet_alloc();
    if (!v->stream || !v->enc || !v->frame || !v->pkt) {
        snprintf(why, (size_t)why_size, "out of memory");
        free_all(v);
        return NULL;
    }
    const AVRational rate = av_d2q(fps, 100000);
    v->enc->width = width;
    v->enc->height = height;
    v->enc->pix_fmt = AV_PIX_FMT_YUV420P;
    v->enc->time_base = av_inv_q(rate);
    v->enc->framerate = rate;
    v->enc->gop_size = 48;
    v->enc->color_range = AVCOL_RANGE_MPEG;
    v->enc->colorspace = AVCOL_SPC_SMPTE170M;
    v->enc->color_primaries = AVCOL_PRI_BT709;
    v->enc->color_trc = AVCOL_TRC_IEC61966_2_1;
    if (v->fmt->oformat->flags & AVFMT_GLOBALHEADER) v->enc->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    set_quality(v->enc, codec, quality);
    if ((err = avcodec_open2(v->enc, codec, NULL)) < 0 ||
        (err = avcodec_parameters_from_context(v->stream->codecpar, v->enc)) < 0) {
        av_reason(why, why_size, "cannot start the encoder", err);
        free_all(v);
        return NULL;
    }
    v->stream->time_base = v->enc->time_base;
    v->stream->avg_frame_rate = rate;
    v->frame->format = v->enc->pix_fmt;
    v->frame->width = width;
    v->frame->height = height;
    if ((err = av_frame_get_buffer(v->frame, 0)) < 0) {
        av_reason(why, why_size, "cannot allocate a frame", err);
        free_all(v);
        return NULL;
    }
    v->sws = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P,
                            SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, NULL, NULL, NULL);
    if (!v->sws) {
        snprintf(why, (size_t)why_size, "no RGBA -> YUV 4:2:0 conversion");
        free_all(v);
        return NULL;
    }
    if (!(v->fmt->oformat->flags & AVFMT_NOFILE) &&
        (err = avio_open(&v->fmt->pb, path, AVIO_FLAG_WRITE)) < 0) {
        av_reason(why, why_size, "cannot create the file", err);
        free_all(v);
        return NULL;
    }
    if ((err = avformat_write_header(v->fmt, NULL)) < 0) {
        av_reason(why, why_size, "cannot write the header", err);
        free_all(v);
        return NULL;
    }
    v->header_written = 1;
    return v;
}

/* Sends a frame (NULL: flush) and writes every packet the encoder gives back. */
static int encode(anim_video *v, const AVFrame *frame, char *why, int why_size) {
    int err = avcodec_send_frame(v->enc, frame);
    if (err < 0) {
        av_reason(why, why_size, "encoding a frame failed", err);
        return -1;
    }
    for (;;) {
        err = avcodec_receive_packet(v->enc, v->pkt);
        if (err == AVERROR(EAGAIN) || err == AVERROR_EOF) return 0;
        if (err < 0) {
            av_reason(why, why_size, "encoding a frame failed", err);
            return -1;
        }
        av_packet_rescale_ts(v->pkt, v->enc->time_base, v->stream->time_base);
        v->pkt->stream_index = v->stream->index;
        err = av_interleaved_write_frame(v->fmt, v->pkt); /* takes the packet's data */
        if (err < 0) {
            av_reason(why, why_size, "writing the film failed", err);
            return -1;
        }
    }
}

int anim_video_add(anim_video *v, const uint8_t *rgba, char *why, int why_size) {
    int err = av_frame_make_writable(v->frame);
    if (err < 0) {
        av_reason(why, why_size, "cannot reuse the frame", err);
        return -1;
    }
    /* Bottom-up rows: start at the top row and step backwards. */
    const int w = v->enc->width, h = v->enc->height;
    const uint8_t *src[1] = {rgba + (size_t)4 * (size_t)w * (size_t)(h - 1)};
    const int stride[1] = {-4 * w};
    sws_scale(v->sws, src, stride, 0, h, v->frame->data, v->frame->linesize);
    v->frame->pts = v->next_pts++;
    return encode(v, v->frame, why, why_size);
}

int anim_video_close(anim_video *v, char *why, int why_size) {
    int rc = 0;
    if (v->header_written) {
        rc = encode(v, NULL, why, why_size);
        const int err = av_write_trailer(v->fmt);
        if (!rc && err < 0) {
            av_reason(why, why_size, "finishing the film failed", err);
            rc = -1;
        }
    }
    free_all(v);
    return rc;
}

__attribute__((visibility("default"))) const anim_video_plugin *cj_video_plugin_v1(void);

const anim_video_plugin *cj_video_plugin_v1(void) {
    static const anim_video_plugin table = {ANIM_VIDEO_PLUGIN_ABI, anim_video_open, anim_video_add,
                                            anim_video_close};
    return &table;
}
