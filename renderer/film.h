#pragma once
/// The rendered image and its AOVs, and the EXR writer (OpenImageIO). Channels:
///   R, G, B      scene-linear radiance (box filter over the pixel)
///   A            share of the pixel's samples whose camera ray hit geometry
///   albedo.R/G/B surface albedo at the first hit (wood: the filtered ring colour)
///   N.X/Y/Z      world-space shading normal at the first hit (facing the camera)
///   Z            distance along the camera's viewing axis to the first hit
///   T            growth time (years) at the first hit on wood
///   knot         knot share (0..1) at the first hit on wood
///   lamella      id of the board at the first sample's hit, -1 if none (not laminated)
///   variance     variance of the pixel's mean luminance: the samples' luminance variance
///                over their count (0 for one sample); what a denoiser trusts the pixel by
///   visibility   share of the first hit's direct light that reached it: the luminance of its
///                unblocked light samples over all of them (1 where none was taken); shadow
///                edges, which the other AOVs do not see, for the denoiser
///   occlusion    how near the first bounce found geometry: the mean over the camera samples
///                that bounced of 1 - t / R for a bounce ray that hit at t within R = 0.15 x
///                the camera ray's length, else 0 (0 with no bounce); the darkening of
///                indirect light into corners, for the denoiser
///   diffuse.R/G/B the part of R, G, B that the first hit's albedo carries: light reflected by
///                the base (and wood's fibre lobe) at the camera ray's hit, whatever path it
///                took there; the rest is the coat's or metal's reflection, or an emitter seen
///                directly. The denoiser divides only this part by the albedo
///   samples      samples the pixel took (adaptive sampling only)
/// Each AOV but lamella is the mean over the samples that contribute to it (hits for albedo,
/// N and Z, wood hits for T and knot); 0 where none did.

#include <map>
#include <string>
#include <vector>

#include "util/zero_page_allocator.h"

namespace nenrin {

/// One channel group of a film: zero until written, cleared by nobody (util/zero_page_allocator.h).
using FilmPlane = std::vector<float, ZeroPageAllocator<float>>;

struct Film {
    int width = 0, height = 0;  ///< the whole frame
    /// The rows the film holds: all of them, unless a split job (--tile) renders a band.
    int firstRow = 0, rows = 0;
    FilmPlane rgb, albedo, normal, diffuse;  ///< 3 per pixel, row firstRow first
    FilmPlane alpha, depth, growthTime, knot, lamella, variance, visibility, occlusion;
    FilmPlane samples;  ///< per pixel; empty unless sampling was adaptive

    /// A frame of w x h holding rows [first, first + count) (count < 0: to the bottom), every
    /// channel new: zero, but lamella -1 and visibility 1.
    void resize(int w, int h, int first = 0, int count = -1);
};

/// The EXR channel names of a film, in file order ("samples" only if sampling was adaptive).
std::vector<std::string> filmChannelNames(bool adaptive);
/// The same channels in words, for the EXR header (nenrin:channels).
std::string filmChannelDescription(bool adaptive);

struct FloatExr;
/// The film a render EXR holds (its channels must be filmChannelNames'); InputError naming
/// `file` otherwise.
Film filmFromExr(const FloatExr& image, const std::string& file);

/// Writes all channels as 32-bit float EXR (zip), atomically; `metadata` goes into the header
/// as nenrin:KEY strings. A band of rows is written as that EXR data window of the frame.
/// `threads` (0 = all cores) compress it (the same bytes for any count).
void writeFilmExr(const Film& film, const std::string& path,
                  const std::map<std::string, std::string>& metadata, int threads = 1);

}  // namespace nenrin
