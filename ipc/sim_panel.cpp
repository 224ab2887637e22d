#include "ipc/sim_panel.hpp"

#include <unistd.h>

#include <cstring>

namespace stepmod::ipc {

SimPanelServer::SimPanelServer(const std::string& name, unsigned axes) : axes_(axes) {
  check_name(name);
  if (axes == 0 || axes > STEPMOD_PANEL_MAX_AXES) throw IpcError("panel: bad number of axes");
  map_ = ShmMapping::create(panel_object(name), STEPMOD_PANEL_SIZE, STEPMOD_PANEL_MAGIC,
                            STEPMOD_PANEL_OFF_OWNER_PID);
  p_ = static_cast<stepmod_panel_t*>(map_.data());
  p_->version = STEPMOD_PANEL_VERSION;
  p_->axes = axes;
  p_->owner_pid = static_cast<std::uint64_t>(::getpid());
  stepmod_publish_magic(p_->magic, STEPMOD_PANEL_MAGIC);  // header before magic, as for the image
}

void SimPanelServer::publish_position(unsigned axis, std::int64_t steps) noexcept {
  if (axis < axes_) __atomic_store_n(&p_->axis[axis].position, steps, __ATOMIC_RELAXED);
}
void SimPanelServer::publish_encoder(unsigned axis, std::int64_t counts) noexcept {
  if (axis < axes_) __atomic_store_n(&p_->axis[axis].encoder, counts, __ATOMIC_RELAXED);
}
void SimPanelServer::publish_outputs(unsigned axis, std::uint32_t levels) noexcept {
  if (axis < axes_) __atomic_store_n(&p_->axis[axis].outputs, levels, __ATOMIC_RELAXED);
}
std::uint32_t SimPanelServer::force_mask(unsigned axis) const noexcept {
  return axis < axes_ ? __atomic_load_n(&p_->axis[axis].force_mask, __ATOMIC_ACQUIRE) : 0;
}
std::uint32_t SimPanelServer::force_levels(unsigned axis) const noexcept {
  return axis < axes_ ? __atomic_load_n(&p_->axis[axis].force_levels, __ATOMIC_ACQUIRE) : 0;
}

SimPanelClient::SimPanelClient(const std::string& name) {
  check_name(name);
  p_ = open_checked<stepmod_panel_t>(
      map_, panel_object(name), STEPMOD_PANEL_SIZE,
      {STEPMOD_PANEL_MAGIC, STEPMOD_PANEL_VERSION, "a stepmod simulator panel", "", "panel"});
  axes_ = p_->axes;
  if (axes_ == 0 || axes_ > STEPMOD_PANEL_MAX_AXES) {
    throw IpcError("/dev/shm" + panel_object(name) + " has an impossible number of axes");
  }
}

void SimPanelClient::check(unsigned axis, unsigned input) const {
  if (axis >= axes_) {
    throw IpcError("axis " + std::to_string(axis + 1) + " out of range 1.." +
                   std::to_string(axes_));
  }
  if (input >= STEPMOD_PANEL_INPUTS) throw IpcError("panel input out of range");
}

PanelAxis SimPanelClient::read(unsigned axis) const {
  check(axis, 0);
  const stepmod_panel_axis_t& a = p_->axis[axis];
  PanelAxis r;
  r.position = __atomic_load_n(&a.position, __ATOMIC_RELAXED);
  r.encoder = __atomic_load_n(&a.encoder, __ATOMIC_RELAXED);
  r.force_mask = __atomic_load_n(&a.force_mask, __ATOMIC_ACQUIRE);
  r.force_levels = __atomic_load_n(&a.force_levels, __ATOMIC_ACQUIRE);
  r.outputs = __atomic_load_n(&a.outputs, __ATOMIC_RELAXED);
  return r;
}

void SimPanelClient::force(unsigned axis, unsigned input, bool level) {
  check(axis, input);
  if (!map_.writable())
    throw IpcError(std::string("simulator panel is read-only for this user (") + kGroupHint + ")");
  stepmod_panel_force(p_, axis, input, level ? 1 : 0);
}

void SimPanelClient::release(unsigned axis, unsigned input) {
  check(axis, input);
  if (!map_.writable())
    throw IpcError(std::string("simulator panel is read-only for this user (") + kGroupHint + ")");
  stepmod_panel_release(p_, axis, input);
}

void SimPanelClient::release_all(unsigned axis) {
  for (unsigned i = 0; i < STEPMOD_PANEL_INPUTS; ++i) release(axis, i);
}

}  // namespace stepmod::ipc
