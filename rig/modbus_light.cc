#include "rig/modbus_light.h"

namespace brdfrig::rig {

ModbusLight::ModbusLight(std::shared_ptr<ModbusLink> link, int slave, int coil)
    : link_(std::move(link)), slave_(slave), coil_(coil) {}

void ModbusLight::SetOn(bool on) { link_->WriteCoil(slave_, coil_, on); }

bool ModbusLight::IsOn() { return link_->ReadCoil(slave_, coil_); }

std::string ModbusLight::Describe() const {
  return "modbus " + link_->options().Endpoint() + " slave " + std::to_string(slave_) + ", coil " +
         std::to_string(coil_);
}

}  // namespace brdfrig::rig
