#pragma once
// `render_bench --present`: the frame of a live node, which stays on the GPU:
// Renderer::render_on_gpu → the display pass band by band
// (DisplayEncoder::encode_band, render/display/display_encoder.h) → drawn in a window
// (render/window/output_windows.h) and swapped; nothing is read back. Timed by
// GL timer queries (GL_TIME_ELAPSED around the GPU's commands: the GPU's own
// time) and by the wall clock (to the completed swap, glFinish), with the
// scene's atmospheres and without (bodies only).
//
// Beside it, "before": the path a node with --window took up to f28d6b6, step
// for step — Renderer::render_image (read back), the display values on the CPU
// (tone mapping), the frame written as a PNG file, the picture uploaded to a
// texture and drawn (render/window/frame_presenter.h), swapped — on the same
// context, scene and size, interleaved frame by frame, so the ratio holds on a
// shared machine. On a CPU rasterizer (Mesa llvmpipe) the GL timer measures the
// CPU's shader work too.
//
//   render_bench --present [--scene FILE] [--size WxH] [--fov DEG] [--frames N] [--rounds R]
//                [--tables paper|small] [--orders N] [--cache DIR] [--csv FILE] [--headless] [--no-before] [--split]
//                [--moving]
//
// --split times the steps apart instead (Renderer::render_to_texture, then
// DisplayEncoder::encode, then the window; glFinish between). --moving turns
// the camera by 1 µrad every frame (bench/moving_camera.h), so that no frame
// reuses the tile classification of a still scene (render/frame/frame_tiles.h).
//
// With DISPLAY set (a desktop, or xvfb-run) the frame goes to a window of the
// frame's size; --headless (or no DISPLAY) renders on a headless EGL context
// and stops at the display texture. CSV (default
// bench/results/present_frame_times.csv), one row per case:
//   device, size, atmospheres, path (live | before), target (window | headless),
//   wall_ms (median), wall_ms_min, gpu_ms (median GL time; live only), frames,
//   cpu_ms (median CPU time of the process per frame, every thread: the driver's and
//   llvmpipe's too; a GPU-bound frame on a GPU costs little of it)
namespace zenith::bench {

/// Runs the benchmark; argv holds "--present" somewhere (ignored). Returns the exit status.
int run_present(int argc, char** argv);

}  // namespace zenith::bench
