// What the adapter's code answers a PLC, per module type, as one JSON object on stdout: the
// Identity object's values, the assembly instances and their sizes, the RPI range of the
// defaults and the number of I/O connections. tests/enip/eds_check.py compares the EDS files
// (packaging/eds/) with it, so that an EDS cannot silently drift from the code.
#include <cstdio>

#include "core/module_shape.hpp"
#include "fieldbus/enip/assembly.hpp"
#include "fieldbus/enip/connection_table.hpp"
#include "fieldbus/enip/forward_open.hpp"
#include "fieldbus/enip/identity.hpp"

namespace {

using namespace stepmod;

void print_module(const ModuleShape& shape, bool last) {
  const enip::IdentityValues id = enip::identity_for(static_cast<std::uint32_t>(shape.type), 0);
  const enip::AssemblyLayout layout =
      enip::assembly_layout(shape.word_bytes, shape.output_words, shape.input_words);
  std::printf(
      "  {\"type\": %u, \"vendor\": %u, \"device_type\": %u, \"product_code\": %u, "
      "\"major\": %u, \"minor\": %u, \"name\": \"%.*s\", \"word_bytes\": %u, "
      "\"input_bytes\": %u, \"output_bytes\": %u}%s\n",
      static_cast<unsigned>(shape.type), id.vendor, id.device_type, id.product_code, id.major,
      id.minor, static_cast<int>(id.product_name().size()), id.product_name().data(),
      shape.word_bytes, layout.input_bytes, layout.output_bytes, last ? "" : ",");
}

}  // namespace

int main() {
  const enip::AdapterLimits limits;
  std::printf(
      "{\"instances\": {\"input\": %u, \"output\": %u, \"config\": %u, "
      "\"input_only\": %u, \"listen_only\": %u},\n",
      enip::kInputInstance, enip::kOutputInstance, enip::kConfigInstance, enip::kInputOnlyHeartbeat,
      enip::kListenOnlyHeartbeat);
  std::printf(" \"rpi_min_us\": %u, \"rpi_max_us\": %u, \"max_io_connections\": %zu,\n",
              limits.rpi_min_us, limits.rpi_max_us, enip::kMaxIoConnections);
  std::printf(" \"modules\": [\n");
  for (std::size_t i = 0; i < kModuleShapes.size(); ++i) {
    print_module(kModuleShapes[i], i + 1 == kModuleShapes.size());
  }
  std::printf(" ]}\n");
  return 0;
}
