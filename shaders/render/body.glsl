// One analytic sphere of the frame: the std430 element of frame.glsl's Bodies
// buffer. Its C++ twin is render/frame/gpu_body.h's GpuBody; the layout is
// checked field by field on the GPU (tests/render/shader_interface_test.cpp,
// tests/shaders/test_body_layout.comp): change both together.
struct Body {
  vec4 centre;          // xyz: unit direction camera → centre (world); w: distance camera → centre [m]
  vec4 shape;           // x: radius R [m]; y: |c|² − R² [m²]; z: atmosphere slot or −1; w: albedo map layer
  vec4 albedo_map;      // x: width of the albedo maps' level 0 [texels]; yzw: unused
  vec4 world_to_body0;  // rows of the rotation world → body frame
  vec4 world_to_body1;
  vec4 world_to_body2;
};
