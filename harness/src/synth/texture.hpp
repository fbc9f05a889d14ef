// texture.hpp — procedural surface textures for the synthetic office: rich in corners and edges at
// several scales (tiles, wood, paint noise, printed pages, posters, carpet), so that FAST/ORB and
// Lucas–Kanade behave as on real indoor images.
//
// Every texture is a function of surface coordinates in metres, filtered by the pixel footprint (the
// size of one pixel on the surface): detail finer than about two footprints fades to its mean, as a
// camera's optics and a mip-map would, instead of aliasing into noise.
#pragma once

#include <Eigen/Core>

#include <cstdint>

namespace vobench::synth {

// Photo: a photo-like print, a 1/f colour field (Field 1987: natural images' amplitude spectra fall
// as 1/f) cut into regions with hard edges. Keys: a keyboard's key grid. Screen: a switched-off
// monitor, nearly black and glossy. Fabric: a fine weave (chairs, curtains).
enum class TextureStyle { Paint, Tiles, Wood, Pages, Poster, Carpet, Photo, Keys, Screen, Fabric };

struct Material {
    TextureStyle style = TextureStyle::Paint;
    Eigen::Vector3f base{0.7f, 0.7f, 0.7f};  // linear RGB albedo in [0, 1]
    Eigen::Vector3f accent{0.2f, 0.2f, 0.2f};
    float scale = 1.0f;  // metres per pattern unit
    uint64_t seed = 0;
    float gloss = 0.0f;     // share of specular (Blinn–Phong) reflection: highlights, and lost depth (sensor_model.hpp)
    float emission = 0.0f;  // linear radiance added regardless of light (windows, lamps): saturates the camera
};

// Albedo at surface point (u, v) (metres) with pixel footprint `footprint` (metres).
Eigen::Vector3f albedo(const Material& m, double u, double v, double footprint);

}  // namespace vobench::synth
