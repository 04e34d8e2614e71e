// The end of the transfer path: conversion of RGBA groups to framebuffer
// fragment colours (GL121 §3.6.4 "Final Conversion" -> §2.13.9) and to texture
// internal formats (§3.8.1, Table 3.15). Both clamp each component to [0,1]
// first; fixed profiles then round the exact value half up to the target width
// (unorm_from_double); float32 stores the binary32 value, ideal the binary64 one.
#pragma once
#include <cstdint>

#include "pipeline/number/profile.h"
#include "pipeline/pixel_transfer/formats.h"
#include "pipeline/pixel_transfer/pixel_image.h"
#include "pipeline/texture/texture_object.h"

namespace ffsim::pixel {

// One component to a fixed-point code of `bits` (clamp01, round half up, exact).
template <class T>
std::uint16_t final_code(T v, int bits);
// One component to a float-profile value (clamp01; binary32 under Float32).
template <class T>
double final_value(T v, Arithmetic a);

// Component width a texture image of format f gets under profile p.
int texture_storage_bits(const InternalFormat& f, const Profile& p);

// A new width x height level (border texels included) of internal format f,
// every component 0.
TextureImage texture_level(int width, int height, GLenum internal_format, const InternalFormat& f, int border,
                           const Profile& p);

// A new texture level from the transferred image (border texels included in
// img: width = w_s + 2*border). Components picked by base format: ALPHA <- A,
// LUMINANCE <- R, LUMINANCE_ALPHA <- R, A, INTENSITY <- R, RGB <- R, G, B,
// RGBA <- R, G, B, A.
template <class T>
TextureImage make_texture_image(const RgbaImage<T>& img, GLenum internal_format, const InternalFormat& f,
                                int border, const Profile& p);
// Writes img into an existing level at storage position (x0, y0) (border
// included, i.e. x0 = xoffset + border), keeping the level's format and width.
template <class T>
void store_texels(const RgbaImage<T>& img, TextureImage& dst, int x0, int y0, const Profile& p);

}  // namespace ffsim::pixel
