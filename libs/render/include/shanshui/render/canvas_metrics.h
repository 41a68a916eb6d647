// Measures of the canvas's temporal coherence and flatness (SPEC.md section 8): the
// warping error between consecutive frames, with the known depth and cameras instead of
// optical flow, and the screen-space peak frequency and contrast of a canvas image.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "shanshui/image/image.h"
#include "shanshui/render/camera.h"

namespace shanshui::render {

class InkRenderer;

//! One rendered view for the warping error: a one-channel image, the world position seen
//! at each pixel (RGBA: xyz, and 1 where known), and the camera that saw it.
struct WarpView {
  image::Image values;
  image::Image positions;
  OrbitCamera camera;
};

//! The world positions of the renderer's last frame: the surface from the depth buffer,
//! and where nothing was drawn the view ray's exit through the canvas's background dome
//! (none without a dynamic canvas: those pixels stay unknown).
image::Image viewPositions(const InkRenderer& renderer, const OrbitCamera& camera);

struct WarpError {
  double mse = 0.0;       //!< mean squared difference over the compared pixels
  double variance = 0.0;  //!< of the current values over the same pixels
  double coverage = 0.0;  //!< fraction of pixels compared
  double relative() const { return variance > 0 ? mse / variance : 0.0; }
};

//! Frame `previous` warped to `current`: each current pixel's position is projected into
//! the previous view and the previous values sampled there bilinearly; pixels that fall
//! outside it, or whose point the previous view saw something else at (view depths more
//! than 2 % apart: an occlusion), are left out.
WarpError warpingError(const WarpView& previous, const WarpView& current);

struct SpectrumPeak {
  double frequency = 0.0;       //!< cycles per pixel: centroid of the radial power above half its maximum
  double mean_frequency = 0.0;  //!< cycles per pixel: power-weighted mean over all rings (broad spectra)
  double contrast = 0.0;        //!< standard deviation
  //! cycles per pixel: the same centroid of the radial energy (ring-summed power, the
  //! energy per unit |f|), which peaks at the cut-off of a low-pass spectrum whose ring
  //! average is flat-topped from 0 (the rice paper's) instead of on its lowest rings
  double energy_frequency = 0.0;
};

//! The ring-averaged periodogram of a one-channel image: mean removed, Hann window, |DFT|²
//! divided by the window's energy (a spectral density per pixel). Element b is the mean
//! over the bins at radius [b, b + 1) / min(w, h) cycles per pixel, for b < min(w, h) / 2;
//! element 0 (the mean) is 0.
std::vector<double> radialPowerSpectrum(const image::Image& img);

//! The share of a one-channel image's power (the same periodogram, mean left out) at
//! frequencies above `frequency` cycles per pixel: how much of a paper is fine static.
double powerShareAbove(const image::Image& img, double frequency);

//! The shares of a one-channel image's power between `low` and `high` cycles per pixel that
//! lie in each of `sectors` equal sectors of orientation over [0°, 180°), sector 0 centred
//! on 0° (frequency vectors along x: stripes across x). A weave puts its power in the
//! sectors of its warp and weft; an isotropic paper spreads it evenly.
std::vector<double> orientationShares(const image::Image& img, int sectors, double low = 0.0, double high = 0.5);

//! The peak of the radially averaged power spectrum (Hann-windowed) of a one-channel image,
//! and its contrast.
SpectrumPeak spectrumPeak(const image::Image& img);
//! The same of the mean spectrum (and mean contrast) of independent realisations of one
//! noise, all one-channel and of one size: where the measured peak lies on rings of many
//! bins, its spread falls about as 1/√count.
SpectrumPeak spectrumPeak(const std::vector<image::Image>& realisations);

}  // namespace shanshui::render
