"""A byte-level Dynamixel servo simulator on a pseudo-terminal, for tests and benchmarks.

It speaks Protocol 2.0 (ping, read, write, sync read, sync write; status packets with
CRC-16 and byte stuffing; the alert bit and Hardware Error Status) and Protocol 1.0
(ping, read, write, sync write; checksum; status error bits). Each servo's present
position moves toward its goal at the model's speed while torque is on. Faults are
scripted: `overload:ID@1.5s` sets the overload bit and drops torque, `silent:ID@1.5s`
stops the servo answering, both counted from the first goal write.

    python -m scriptc.player.servo_sim --ids 1-10 [--protocol 2] [--model xm430]
        [--fault overload:3@2s] [--record goals.jsonl]

prints the pseudo-terminal's path on its first line and serves until killed.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import select
import sys
import time
import tty
from dataclasses import dataclass, field
from typing import IO

from scriptc import units
from scriptc.player.dxl_tables import MODELS, Model, Reg

INST_PING, INST_READ, INST_WRITE, INST_SYNC_READ, INST_SYNC_WRITE = 0x01, 0x02, 0x03, 0x82, 0x83
STATUS = 0x55
ERR_ALERT = 0x80
OVERLOAD_P2, OVERLOAD_P1 = 1 << 5, 1 << 5


def crc16(data: bytes) -> int:
    """CRC-16 of Protocol 2.0 (polynomial 0x8005, initial 0, not reflected)."""
    crc = 0
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x8005) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def stuff(body: bytes) -> bytes:
    """Insert 0xFD after every FF FF FD inside instruction/status bodies."""
    out = bytearray()
    for b in body:
        out.append(b)
        if len(out) >= 3 and out[-3:] == b"\xff\xff\xfd":
            out.append(0xFD)
    return bytes(out)


def unstuff(body: bytes) -> bytes:
    out = bytearray()
    i = 0
    while i < len(body):
        out.append(body[i])
        if (
            len(out) >= 3
            and out[-3:] == b"\xff\xff\xfd"
            and i + 1 < len(body)
            and body[i + 1] == 0xFD
        ):
            i += 1
        i += 1
    return bytes(out)


def packet_p2(dxl_id: int, instruction: int, params: bytes) -> bytes:
    body = stuff(bytes([instruction]) + params)
    head = b"\xff\xff\xfd\x00" + bytes([dxl_id]) + (len(body) + 2).to_bytes(2, "little") + body
    return head + crc16(head).to_bytes(2, "little")


def packet_p1(dxl_id: int, first: int, params: bytes) -> bytes:
    body = bytes([dxl_id, len(params) + 2, first]) + params
    return b"\xff\xff" + body + bytes([(~sum(body)) & 0xFF])


@dataclass
class Servo:
    id: int
    model: Model
    table: bytearray = field(default_factory=lambda: bytearray(256))
    position: float = 0.0  # ticks
    silent: bool = False

    def __post_init__(self) -> None:
        self.position = float(self.model.center)
        self.put(Reg.MODEL_NUMBER, self.model.model_number)
        self.put(Reg.GOAL_POSITION, self.model.center)
        self.put(Reg.PRESENT_POSITION, self.model.center)

    def get(self, reg: Reg) -> int:
        addr, size = self.model.regs[reg]
        return int.from_bytes(self.table[addr : addr + size], "little")

    def put(self, reg: Reg, value: int) -> None:
        addr, size = self.model.regs[reg]
        self.table[addr : addr + size] = int(value).to_bytes(size, "little", signed=False)

    def advance(self, dt: float) -> None:
        if not self.get(Reg.TORQUE_ENABLE):
            return
        goal = self.get(Reg.GOAL_POSITION)
        step = self.model.max_speed * dt * self.model.ticks / self.model.span_rad
        delta = goal - self.position
        self.position = (
            goal if abs(delta) <= step else self.position + step * (1 if delta > 0 else -1)
        )
        self.put(Reg.PRESENT_POSITION, round(self.position))


class Simulator:
    def __init__(
        self,
        ids: list[int],
        model: Model,
        faults: list[tuple[str, int, float]],
        record: IO[str] | None = None,
    ) -> None:
        self.model = model
        self.servos = {i: Servo(i, model) for i in ids}
        self.faults = sorted(faults, key=lambda f: f[2])
        self.record = record
        self.started: float | None = None
        self.last = time.monotonic()
        self.hw_reg = model.regs.get(Reg.HARDWARE_ERROR)
        self.error_bits: dict[int, int] = {}

    # -- time and faults --------------------------------------------------------------

    def tick(self) -> None:
        now = time.monotonic()
        for servo in self.servos.values():
            servo.advance(now - self.last)
        self.last = now
        while self.started is not None and self.faults and now - self.started >= self.faults[0][2]:
            kind, dxl_id, _ = self.faults.pop(0)
            target = self.servos.get(dxl_id)
            if target is None:
                continue
            if kind == "silent":
                target.silent = True
            else:
                self.error_bits[dxl_id] = OVERLOAD_P2
                if self.hw_reg:
                    target.table[self.hw_reg[0]] = OVERLOAD_P2
                target.put(Reg.TORQUE_ENABLE, 0)

    def on_write(self, servo: Servo, addr: int, data: bytes) -> None:
        if servo.id in self.error_bits and addr == self.model.regs[Reg.TORQUE_ENABLE][0]:
            return  # a servo in shutdown keeps its torque off
        servo.table[addr : addr + len(data)] = data
        goal_addr = self.model.regs[Reg.GOAL_POSITION][0]
        if addr == goal_addr:
            if self.started is None:
                self.started = time.monotonic()
            if self.record:
                self.record.write(
                    json.dumps(
                        {
                            "t": time.monotonic(),
                            "id": servo.id,
                            "goal": servo.get(Reg.GOAL_POSITION),
                            "torque": servo.get(Reg.TORQUE_ENABLE),
                        }
                    )
                    + "\n"
                )
                self.record.flush()

    # -- Protocol 2.0 -----------------------------------------------------------------

    def status2(self, servo: Servo, params: bytes = b"") -> bytes:
        err = ERR_ALERT if servo.id in self.error_bits else 0
        return packet_p2(servo.id, STATUS, bytes([err]) + params)

    def handle2(self, dxl_id: int, inst: int, p: bytes) -> list[bytes]:
        self.tick()
        replies: list[bytes] = []
        if inst == INST_SYNC_WRITE:
            addr, size = int.from_bytes(p[0:2], "little"), int.from_bytes(p[2:4], "little")
            for i in range(4, len(p), size + 1):
                servo = self.servos.get(p[i])
                if servo is not None:
                    self.on_write(servo, addr, p[i + 1 : i + 1 + size])
            return replies
        if inst == INST_SYNC_READ:
            addr, size = int.from_bytes(p[0:2], "little"), int.from_bytes(p[2:4], "little")
            for sid in p[4:]:
                servo = self.servos.get(sid)
                if servo is None or servo.silent:
                    break  # the rest of the chain waits for a reply that never comes
                replies.append(self.status2(servo, bytes(servo.table[addr : addr + size])))
            return replies
        servo = self.servos.get(dxl_id)
        if servo is None or servo.silent:
            return replies
        if inst == INST_PING:
            replies.append(
                self.status2(servo, self.model.model_number.to_bytes(2, "little") + b"\x2d")
            )
        elif inst == INST_READ:
            addr, size = int.from_bytes(p[0:2], "little"), int.from_bytes(p[2:4], "little")
            replies.append(self.status2(servo, bytes(servo.table[addr : addr + size])))
        elif inst == INST_WRITE:
            self.on_write(servo, int.from_bytes(p[0:2], "little"), p[2:])
            replies.append(self.status2(servo))
        return replies

    def feed2(self, buf: bytearray) -> list[bytes]:
        out: list[bytes] = []
        while True:
            start = buf.find(b"\xff\xff\xfd\x00")
            if start < 0:
                del buf[:-3]
                return out
            del buf[:start]
            if len(buf) < 7:
                return out
            length = int.from_bytes(buf[5:7], "little")
            if len(buf) < 7 + length:
                return out
            frame = bytes(buf[: 7 + length])
            del buf[: 7 + length]
            if crc16(frame[:-2]) != int.from_bytes(frame[-2:], "little"):
                continue  # a real servo drops a packet with a bad CRC
            body = unstuff(frame[7:-2])
            out += self.handle2(frame[4], body[0], body[1:])

    # -- Protocol 1.0 -----------------------------------------------------------------

    def handle1(self, dxl_id: int, inst: int, p: bytes) -> list[bytes]:
        self.tick()
        if inst == INST_SYNC_WRITE:
            addr, size = p[0], p[1]
            for i in range(2, len(p), size + 1):
                servo = self.servos.get(p[i])
                if servo is not None:
                    self.on_write(servo, addr, p[i + 1 : i + 1 + size])
            return []
        servo = self.servos.get(dxl_id)
        if servo is None or servo.silent:
            return []
        err = self.error_bits.get(dxl_id, 0)
        if inst == INST_PING:
            return [packet_p1(dxl_id, err, b"")]
        if inst == INST_READ:
            return [packet_p1(dxl_id, err, bytes(servo.table[p[0] : p[0] + p[1]]))]
        if inst == INST_WRITE:
            self.on_write(servo, p[0], p[1:])
            return [packet_p1(dxl_id, err, b"")]
        return []

    def feed1(self, buf: bytearray) -> list[bytes]:
        out: list[bytes] = []
        while True:
            start = buf.find(b"\xff\xff")
            if start < 0 or len(buf) < start + 4:
                return out
            del buf[:start]
            length = buf[3]
            if len(buf) < 4 + length:
                return out
            frame = bytes(buf[: 4 + length])
            del buf[: 4 + length]
            if (~sum(frame[2:-1])) & 0xFF != frame[-1]:
                continue
            out += self.handle1(frame[2], frame[4], frame[5:-1])


def _parse_fault(text: str) -> tuple[str, int, float]:
    kind, _, rest = text.partition(":")
    sid, _, at = rest.partition("@")
    if kind not in ("overload", "silent") or not sid.isdigit():
        raise argparse.ArgumentTypeError(
            f"bad fault {text!r}: use overload:ID@1.5s or silent:ID@1.5s"
        )
    return kind, int(sid), units.duration_ms(at or "0ms") / 1000.0


def _parse_ids(text: str) -> list[int]:
    ids: list[int] = []
    for part in text.split(","):
        lo, _, hi = part.partition("-")
        ids += list(range(int(lo), int(hi or lo) + 1))
    return ids


def serve(sim: Simulator, master: int, protocol: int) -> None:
    buf = bytearray()
    feed = sim.feed2 if protocol == 2 else sim.feed1
    while True:
        ready, _, _ = select.select([master], [], [], 0.05)
        if not ready:
            sim.tick()
            continue
        try:
            data = os.read(master, 4096)
        except OSError:
            time.sleep(0.01)  # no reader on the other side yet
            continue
        buf += data
        for reply in feed(buf):
            os.write(master, reply)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="servo_sim", description=__doc__.splitlines()[0])
    ap.add_argument("--ids", type=_parse_ids, default=_parse_ids("1-10"))
    ap.add_argument("--protocol", type=int, choices=(1, 2), default=2)
    ap.add_argument(
        "--model", default=None, help="servo model (default xm430, or ax12 for protocol 1)"
    )
    ap.add_argument("--fault", type=_parse_fault, action="append", default=[])
    ap.add_argument("--record", default=None, help="write every goal write as JSON lines here")
    args = ap.parse_args(argv)
    model = MODELS[args.model or ("xm430" if args.protocol == 2 else "ax12")]
    if model.protocol != args.protocol:
        ap.error(f"{model.name} speaks protocol {model.protocol}")
    master, slave = os.openpty()
    tty.setraw(slave)
    record = open(args.record, "a", encoding="utf-8") if args.record else None  # noqa: SIM115
    print(os.ttyname(slave), flush=True)
    with contextlib.suppress(KeyboardInterrupt):
        serve(Simulator(args.ids, model, args.fault, record), master, args.protocol)
    return 0


if __name__ == "__main__":
    sys.exit(main())
