#pragma once
// The tables `zenith validate` asks for (validate/validation_tables.h), from
// the table request its command line built: the cache, else a precompute on
// the GPU or the CPU (render/lut/table_provider.h).
#include <string>
#include <utility>

#include "render/lut/table_provider.h"
#include "validate/validation_tables.h"

namespace zenith::app {

inline validate::TablesFor validation_tables(render::TableRequest request) {
  return [request = std::move(request)](const atmosphere::AtmosphereModel& model) {
    render::ObtainedTables t = render::obtain_tables(model, request);
    return validate::ValidationTables{std::move(t.tables),
                                      t.from_cache ? std::string("cache") : "computed on " + t.report.device};
  };
}

}  // namespace zenith::app
