#!/bin/sh
# The include arrows of docs/ARCHITECTURE.md that the build alone does not enforce (every folder
# sees the source root): module/ sees no GPIO, daemon, config or stepmodctl code (its I/O comes
# through module/axis/axis_io.hpp); web/ and config/ do not reach into the daemon or stepmodctl;
# daemon/ not into stepmodctl; and no code asks a backend what it is with dynamic_cast.
# Usage: layers_test.sh SOURCE_DIR
src=${1:?usage: layers_test.sh SOURCE_DIR}
cd "$src" || exit 2
status=0
forbid() {  # FOLDER PATTERN WHY
  hits=$(grep -rnE --include='*.hpp' --include='*.cpp' "$2" "$1" 2>/dev/null)
  if [ -n "$hits" ]; then
    printf '%s\n%s\n' "$1/ $3:" "$hits" >&2
    status=1
  fi
}
forbid module '#include "(gpio|daemon|config|tools)/' 'must not include gpio/, daemon/, config/ or tools/'
forbid web '#include "(daemon|tools)/' 'must not include daemon/ or tools/ (the configuration: config/)'
forbid config '#include "(daemon|tools)/' 'must not include daemon/ or tools/'
forbid daemon '#include "tools/' 'must not include tools/ (stepmodctl)'
for d in core gpio ipc module planner rt words plc registry config daemon tools web systemd; do
  forbid "$d" 'dynamic_cast<[^>]*Backend' 'must not dynamic_cast a backend (daemon/backend_factory.hpp hands out the simulator by type)'
done
[ "$status" -eq 0 ] && echo "include arrows as documented"
exit "$status"
