// A light switched by a Modbus coil (a relay output of a drive, PLC or I/O module).
#pragma once

#include <memory>
#include <string>

#include "rig/axis.h"
#include "rig/modbus_link.h"

namespace brdfrig::rig {

class ModbusLight : public Light {
 public:
  ModbusLight(std::shared_ptr<ModbusLink> link, int slave, int coil);
  // Writes the coil; a failure (after the link's retries) throws ModbusError.
  void SetOn(bool on) override;
  bool IsOn();  // reads the coil back
  std::string Describe() const;

 private:
  std::shared_ptr<ModbusLink> link_;
  int slave_;
  int coil_;
};

}  // namespace brdfrig::rig
