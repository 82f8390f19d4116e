"""Real servos through `dynamixel_sdk`: Protocol 2.0 (X series) and 1.0 (AX/MX).

This output is the only code that touches the bus, from the streamer's thread. Goal
positions for every joint go out in one GroupSyncWrite per tick. Health checks read
Hardware Error Status with a GroupSyncRead (Protocol 2.0) or each servo's status
error byte in turn (1.0). A servo that stops answering is found by pinging each one.
"""

from __future__ import annotations

from typing import Any

from scriptc.player import dxl_tables
from scriptc.player.dxl_tables import Reg
from scriptc.player.plan import JointSpec
from scriptc.player.servo_out import ServoFault, ServoOutput

INSTALL = "pip install dynamixel-sdk"


def _sdk() -> Any:
    try:
        import dynamixel_sdk
    except ImportError:  # pragma: no cover - it is a dependency
        raise ServoFault(f"dynamixel_sdk is not installed: {INSTALL}") from None
    return dynamixel_sdk


class DynamixelOutput(ServoOutput):
    def __init__(
        self,
        robot: str,
        joints: dict[str, JointSpec],
        bus: dict[str, Any],
        *,
        port: str | None = None,
    ) -> None:
        self.robot = robot
        self.joints = joints
        self.port_name = port or str(bus["port"])
        self.baud = int(bus.get("baud", 1_000_000))
        self.model = dxl_tables.get(str(bus.get("model", "xm430")))
        self.protocol = int(bus.get("protocol", self.model.protocol))
        self.ids = {j.id: j.name for j in joints.values()}
        self.sdk = _sdk()
        self.port: Any = None
        self.packets: Any = None
        self.sync_write: Any = None
        self.sync_read: Any = None
        self._round_robin = 0
        self._bytes = 0

    def _count_bytes(self, port: Any) -> None:
        """Count every byte the SDK writes to and reads from the port."""
        write, read = port.writePort, port.readPort

        def counted_write(packet: Any) -> Any:
            self._bytes += len(packet)
            return write(packet)

        def counted_read(length: int) -> Any:
            data = read(length)
            self._bytes += len(data)
            return data

        port.writePort, port.readPort = counted_write, counted_read

    def bus_bytes(self) -> int:
        return self._bytes

    def _ok(self, result: int) -> bool:
        return bool(result == self.sdk.COMM_SUCCESS)

    def open(self) -> dict[str, float]:
        sdk = self.sdk
        self.port = sdk.PortHandler(self.port_name)
        try:
            opened = self.port.openPort() and self.port.setBaudRate(self.baud)
        except Exception as exc:
            raise ServoFault(
                f"{self.robot}: cannot open servo bus {self.port_name}: {exc}"
            ) from None
        self._count_bytes(self.port)
        if not opened:
            raise ServoFault(
                f"{self.robot}: cannot open servo bus {self.port_name} at {self.baud} baud"
            )
        self.packets = sdk.PacketHandler(float(self.protocol))
        missing = [i for i in self.ids if not self._ok(self.packets.ping(self.port, i)[1])]
        if missing:
            names = ", ".join(f"{i} ({self.ids[i]})" for i in missing)
            raise ServoFault(f"{self.robot}: servos {names} do not answer on {self.port_name}")
        self.check()
        addr, _ = self.model.regs[Reg.TORQUE_ENABLE]
        for i in self.ids:
            result, error = self.packets.write1ByteTxRx(self.port, i, addr, 1)
            if not self._ok(result) or error:
                raise ServoFault(f"{self.robot}: cannot switch on torque of servo {i}", servo=i)
        goal_addr, goal_size = self.model.regs[Reg.GOAL_POSITION]
        self.sync_write = sdk.GroupSyncWrite(self.port, self.packets, goal_addr, goal_size)
        for i in self.ids:
            self.sync_write.addParam(i, [0] * goal_size)
        if self.protocol == 2:
            hw_addr, _ = self.model.regs[Reg.HARDWARE_ERROR]
            self.sync_read = sdk.GroupSyncRead(self.port, self.packets, hw_addr, 1)
            for i in self.ids:
                self.sync_read.addParam(i)
        return self._present()

    def _present(self) -> dict[str, float]:
        addr, size = self.model.regs[Reg.PRESENT_POSITION]
        pose = {}
        for i, name in self.ids.items():
            read = self.packets.read4ByteTxRx if size == 4 else self.packets.read2ByteTxRx
            value, result, _ = read(self.port, i, addr)
            if not self._ok(result):
                raise ServoFault(
                    f"{self.robot}: cannot read the position of servo {i} ({name})", servo=i
                )
            pose[name] = self.model.to_rad(int(value))
        return pose

    def write(self, t_ms: float, targets: dict[str, float]) -> None:
        _, size = self.model.regs[Reg.GOAL_POSITION]
        for name, rad in targets.items():
            tick = self.model.to_tick(rad)
            self.sync_write.changeParam(self.joints[name].id, list(tick.to_bytes(size, "little")))
        result = self.sync_write.txPacket()
        if not self._ok(result):
            raise ServoFault(
                f"{self.robot}: writing goal positions failed: {self.packets.getTxRxResult(result)}"
            )

    def _error(self, servo: int, bits: int, table: dict[int, str]) -> ServoFault:
        """The fault for a servo reporting error `bits`, named by id and joint."""
        return ServoFault(
            f"{self.robot}: servo {servo} ({self.ids[servo]}): {dxl_tables.describe(bits, table)}",
            servo=servo,
        )

    def _silent(self) -> list[int]:
        return [i for i in self.ids if not self._ok(self.packets.ping(self.port, i)[1])]

    def check(self) -> None:
        if self.protocol == 2:
            self._check_p2()
        else:
            self._check_p1()

    def _check_p2(self) -> None:
        if self.sync_read is None:
            hw_addr, _ = self.model.regs[Reg.HARDWARE_ERROR]
            for i in self.ids:
                bits, result, _ = self.packets.read1ByteTxRx(self.port, i, hw_addr)
                if self._ok(result) and bits:
                    raise self._error(i, bits, dxl_tables.HW_ERRORS_P2)
            return
        hw_addr, _ = self.model.regs[Reg.HARDWARE_ERROR]
        if not self._ok(self.sync_read.txRxPacket()):
            silent = self._silent()
            which = ", ".join(f"{i} ({self.ids[i]})" for i in silent) or "?"
            raise ServoFault(
                f"{self.robot}: servo {which} stopped answering",
                servo=silent[0] if silent else None,
            )
        for i in self.ids:
            bits = int(self.sync_read.getData(i, hw_addr, 1))
            if bits:
                raise self._error(i, bits, dxl_tables.HW_ERRORS_P2)

    def _check_p1(self) -> None:
        ids = list(self.ids)
        i = ids[self._round_robin % len(ids)]
        self._round_robin += 1
        _, result, error = self.packets.read2ByteTxRx(
            self.port, i, self.model.regs[Reg.PRESENT_POSITION][0]
        )
        if not self._ok(result):
            raise ServoFault(f"{self.robot}: servo {i} ({self.ids[i]}) stopped answering", servo=i)
        if error:
            raise self._error(i, error, dxl_tables.STATUS_ERRORS_P1)

    def close(self) -> None:
        if self.port is not None and getattr(self.port, "is_open", False):
            self.port.closePort()
        self.port = None
