// Height fields from image files and bumpshadow maps to image files (the I/O
// half of bumpshadow, which itself may not depend on sim or OpenImageIO).
#pragma once
#include <string>

#include "bumpshadow/encodings.h"
#include "bumpshadow/heightfield.h"
#include "bumpshadow/horizon.h"
#include "sim/image_io.h"

namespace ffsim {

// Reads an 8/16-bit PNG or TIFF or an EXR through read_image (sim/image_io.h)
// and takes channel 0 (grey, or red of a colour image): height = value * scale,
// value = code / (2^bits - 1) for integer files, the float itself for EXR.
// Image rows are bottom to top, so image row 0 is v = 0. Errors (ImageError or
// HeightFieldError) start with the file name: unreadable or corrupt files,
// non-finite samples, images with a side below 2 texels, scale not finite > 0.
bumpshadow::HeightField load_heightfield(const std::string& path, double scale, bumpshadow::Border border);

// Map images: a FloatMap as F32 (EXR), a ByteMap as U8 (PNG). Channels carried over.
Image float_map_image(const bumpshadow::FloatMap& m);
Image byte_map_image(const bumpshadow::ByteMap& m);
// The heights themselves as a one-channel F32 image (texel units).
Image heightfield_image(const bumpshadow::HeightField& hf);
// Horizon elevations (radians) of azimuths 4g .. 4g+3 as an RGBA F32 image
// (missing azimuths of the last group are 0).
Image horizon_group_image(const bumpshadow::HorizonMap& h, int group);

}  // namespace ffsim
