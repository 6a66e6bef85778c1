#pragma once
// The passes that draw one band's tiles (render/renderer.h lists them), by
// what the tiles hold (render/frame/tile_classification.h): the direct light
// where no atmosphere is, then per light of the atmospheres (the sun, then the
// Moon added) the one-pass atmosphere tiles and the G-buffer path where shells
// overlap. Each issues its GL calls in the renderer's order, so the images
// stay the same bit for bit.
#include "render/band/band_resources.h"
#include "render/frame/frame_in_progress.h"
#include "render/frame/pass_timer.h"
#include "render/frame/tile_classification.h"

namespace zenith::render {

/// direct_light.comp's uniforms for the frame: the colour matrix of the
/// bodies' albedo and, where the sun can be drawn, its colour as a polynomial in μ
/// (the limb darkening summed over the wavelengths).
void set_direct_light_uniforms(FrameInProgress& frame);

/// Tiles no atmosphere touches: bodies and the sun, one pass each, every wavelength.
void draw_direct_tiles(FrameInProgress& frame, const BandTiles& band, PassTimer& timer);

/// The atmosphere tiles lit by `light`: a pass per wavelength group and tile
/// variant where one shell touches the tile, straight to the band's output;
/// then the G-buffer path (the bodies, per group the atmospheres front to back
/// and the resolve). The sun's passes start the output; another light's add to it.
void draw_atmosphere_tiles(FrameInProgress& frame, BandResources& resources, const BandTiles& band,
                           const FrameLight& light, PassTimer& timer);

}  // namespace zenith::render
