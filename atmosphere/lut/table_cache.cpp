#include "atmosphere/lut/table_cache.h"

#include "core/sha256.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputPart.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "atmosphere/model_hash.h"

namespace zenith::atmosphere::lut {
namespace {

/// A table viewed as a 2D float image: 3D tables stack their depth slices vertically.
struct PartView {
  const char* name;
  std::size_t width, height, channels;
  float* data;
};

std::vector<PartView> parts_of(LookupTables& t) {
  auto v3 = [](const char* name, Table3D& x) {
    return PartView{name, x.width, x.height * x.depth, x.channels, x.data.data()};
  };
  return {
      PartView{"transmittance", t.transmittance.width, t.transmittance.height, t.channels, t.transmittance.data.data()},
      PartView{"irradiance", t.irradiance.width, t.irradiance.height, t.channels, t.irradiance.data.data()},
      v3("single_rayleigh", t.single_rayleigh), v3("single_mie", t.single_mie), v3("multiple", t.multiple)};
}

std::string channel_name(std::size_t c) {
  std::ostringstream s;
  s << 'w' << (c < 10 ? "0" : "") << c;
  return s.str();
}

const std::string& string_attribute(const Imf::Header& h, const char* name) {
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
  if (!a) throw std::runtime_error(std::string("missing header attribute ") + name);
  return a->value();
}

int int_attribute(const Imf::Header& h, const char* name) {
  const auto* a = h.findTypedAttribute<Imf::IntAttribute>(name);
  if (!a) throw std::runtime_error(std::string("missing header attribute ") + name);
  return a->value();
}

}  // namespace

std::filesystem::path default_cache_directory() {
  if (const char* dir = std::getenv("ZENITH_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "zenith";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "zenith";
  return ".zenith-cache";
}

/// Revision of the precompute's method: tables computed by an older method
/// under the same options must not be reused. 2: the scattering density by
/// spherical harmonics (the density line below names the method);
/// 3: the second order's source reads the single-scattering tables
/// geometrically in μs (sample_scattering_table_geometric_mu_s); 4: view-ray
/// samples crowded toward the ray's lowest point, T accumulated along the ray
/// (quadrature.h, view_ray_samples); 5: ν slices uniform in the azimuth
/// between view and sun at each μ, μs (scattering_u_nu); 6: the scattering
/// density along the rays and the last order's radiance read geometrically in
/// μs (sample_scattering_table_geometric_mu_s).
constexpr int kPrecomputeMethodRevision = 6;

std::string table_set_key(const AtmosphereModel& model, const PrecomputeOptions& o) {
  std::ostringstream s;
  s << "cache v" << kCacheFormatVersion << " method " << kPrecomputeMethodRevision << '\n'
    << lookup_table_hash(model) << '\n'
    << o.sizes.describe() << '\n'
    << "orders " << o.max_orders << " tolerance " << o.tolerance << (o.series_tail ? " series tail" : "") << '\n'
    << "samples " << o.transmittance_samples << ' ' << o.scattering_samples << ' ' << o.sphere_zenith_samples << '\n'
    << "coarse rays " << o.coarse_ray_stride << " from order " << o.coarse_ray_first_order << '\n'
    << "quadrature " << int(o.scattering_quadrature) << '\n'
    << "density " << (o.density_method == PrecomputeOptions::DensityMethod::Harmonics ? "harmonics " : "direct ")
    << o.harmonic_degree << '\n';
  const std::string text = s.str();
  return core::sha256_hex(text.data(), text.size());
}

void write_tables_exr(const std::filesystem::path& path, const AtmosphereModel& model, const std::string& key,
                      const LookupTables& tables_in) {
  LookupTables& tables =
      const_cast<LookupTables&>(tables_in);  // Imf slices take non-const pointers; nothing is written.
  std::vector<PartView> parts = parts_of(tables);
  std::vector<Imf::Header> headers;
  std::ostringstream wavelengths;
  for (double w : model.wavelengths_nm) wavelengths << w << ' ';
  // Multi-part files share their display window; each part's data window is its own size.
  std::size_t max_w = 0, max_h = 0;
  for (const PartView& p : parts) max_w = std::max(max_w, p.width), max_h = std::max(max_h, p.height);
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(int(max_w) - 1, int(max_h) - 1));
  for (const PartView& p : parts) {
    Imf::Header h(display, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(int(p.width) - 1, int(p.height) - 1)));
    h.setName(p.name);
    h.setType(Imf::SCANLINEIMAGE);
    // Uncompressed: ZIP saved 16 % of the file (float tables hardly compress)
    // and cost 0.55 s of CPU per set written, five times per set in a local
    // cluster (the master's cache and each node's): 8 s of a cold 3-set show's
    // 2-core time. Files written with ZIP before are still read.
    h.compression() = Imf::NO_COMPRESSION;
    for (std::size_t c = 0; c < p.channels; ++c) h.channels().insert(channel_name(c), Imf::Channel(Imf::FLOAT));
    h.insert("zenith.format", Imf::IntAttribute(kCacheFormatVersion));
    h.insert("zenith.key", Imf::StringAttribute(key));
    h.insert("zenith.hash", Imf::StringAttribute(tables.hash));
    h.insert("zenith.sizes", Imf::StringAttribute(tables.sizes.describe()));
    h.insert("zenith.orders", Imf::IntAttribute(tables.scattering_orders));
    h.insert("zenith.wavelengths_nm", Imf::StringAttribute(wavelengths.str()));
    h.insert("zenith.parameters", Imf::StringAttribute(canonical_description(model)));
    h.insert("zenith.checksum",
             Imf::StringAttribute(core::sha256_hex(p.data, p.width * p.height * p.channels * sizeof(float))));
    headers.push_back(h);
  }
  Imf::MultiPartOutputFile file(path.c_str(), headers.data(), int(headers.size()));
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const PartView& p = parts[i];
    Imf::OutputPart part(file, int(i));
    Imf::FrameBuffer fb;
    const std::size_t xs = p.channels * sizeof(float), ys = xs * p.width;
    for (std::size_t c = 0; c < p.channels; ++c)
      fb.insert(channel_name(c), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(p.data + c), xs, ys));
    part.setFrameBuffer(fb);
    part.writePixels(int(p.height));
  }
}

LookupTables read_tables_exr(const std::filesystem::path& path, const AtmosphereModel& model, const std::string& key) {
  try {
    Imf::MultiPartInputFile file(path.c_str());
    if (file.parts() != 5) throw std::runtime_error("expected 5 parts, found " + std::to_string(file.parts()));
    const Imf::Header& first = file.header(0);
    if (int_attribute(first, "zenith.format") != kCacheFormatVersion)
      throw std::runtime_error("format version differs");
    if (string_attribute(first, "zenith.key") != key) throw std::runtime_error("table-set key differs");
    if (string_attribute(first, "zenith.parameters") != canonical_description(model))
      throw std::runtime_error("parameters differ");
    // Sizes come back from the header; they are part of the key, so they match.
    const std::string sizes_text = string_attribute(first, "zenith.sizes");
    TableSizes sizes;
    char t, e, s, x;
    std::istringstream in(sizes_text);
    in >> t >> sizes.transmittance_mu >> x >> sizes.transmittance_r >> e >> sizes.irradiance_mu_s >> x >>
        sizes.irradiance_r >> s >> sizes.scattering_r >> x >> sizes.scattering_mu >> x >> sizes.scattering_mu_s >> x >>
        sizes.scattering_nu;
    if (!in || sizes.describe() != sizes_text) throw std::runtime_error("unreadable table sizes '" + sizes_text + "'");
    LookupTables tables =
        LookupTables::allocate({model.ground_radius_m, model.top_radius_m}, sizes, model.wavelength_count());
    tables.hash = string_attribute(first, "zenith.hash");
    tables.scattering_orders = int_attribute(first, "zenith.orders");
    std::vector<PartView> parts = parts_of(tables);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const PartView& p = parts[i];
      const Imf::Header& h = file.header(int(i));
      const Imath::Box2i dw = h.dataWindow();
      if (h.name() != p.name || std::size_t(dw.max.x - dw.min.x + 1) != p.width ||
          std::size_t(dw.max.y - dw.min.y + 1) != p.height)
        throw std::runtime_error(std::string("part ") + p.name + " has the wrong name or size");
      Imf::InputPart part(file, int(i));
      Imf::FrameBuffer fb;
      const std::size_t xs = p.channels * sizeof(float), ys = xs * p.width;
      for (std::size_t c = 0; c < p.channels; ++c) {
        if (!h.channels().findChannel(channel_name(c)))
          throw std::runtime_error(std::string("part ") + p.name + " lacks channel " + channel_name(c));
        fb.insert(channel_name(c), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(p.data + c), xs, ys));
      }
      part.setFrameBuffer(fb);
      part.readPixels(dw.min.y, dw.max.y);
      const std::size_t count = p.width * p.height * p.channels;
      if (core::sha256_hex(p.data, count * sizeof(float)) != string_attribute(h, "zenith.checksum"))
        throw std::runtime_error(std::string("part ") + p.name + " fails its checksum");
      for (std::size_t k = 0; k < count; ++k)
        if (!std::isfinite(p.data[k]) || p.data[k] < 0.0f)
          throw std::runtime_error(std::string("part ") + p.name + " holds a non-finite or negative value");
    }
    return tables;
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

TableCache::TableCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path TableCache::path_for(const std::string& key) const {
  return directory_ / ("tables-" + key.substr(0, 32) + ".exr");
}

std::optional<LookupTables> TableCache::load(const AtmosphereModel& model, const PrecomputeOptions& options,
                                             std::string* problem) const {
  const std::string key = table_set_key(model, options);
  const std::filesystem::path path = path_for(key);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  try {
    return read_tables_exr(path, model, key);
  } catch (const std::exception& e) {
    if (problem) *problem = e.what();
    return std::nullopt;
  }
}

std::filesystem::path TableCache::store(const AtmosphereModel& model, const PrecomputeOptions& options,
                                        const LookupTables& tables) const {
  std::filesystem::create_directories(directory_);
  const std::string key = table_set_key(model, options);
  const std::filesystem::path path = path_for(key);
  const std::filesystem::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  write_tables_exr(tmp, model, key, tables);
  std::filesystem::rename(tmp, path);
  return path;
}

}  // namespace zenith::atmosphere::lut
