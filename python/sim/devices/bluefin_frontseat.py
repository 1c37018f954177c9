"""A Bluefin vehicle at the wire: the vehicle's side of its standard payload
interface (Huxley's BPI), bytes in and bytes out.

The side auv-frontseat does not speak (c/frontseat/bluefin.c; docs/frontseat.md,
"Bluefin", names the one public source of every field). NMEA 0183 lines, the
payload's $BP..., the vehicle's $BF...:

    payload -> vehicle  $BPLOG,ID,ON|OFF     send sentence ID from now on (or stop)
                        $BPSTS,TIME,1|0,TEXT the payload's heartbeat
                        $BPRMB,TIME,HDG,DEPTH,0,SPEED,1,0
                                             a request: heading [deg], depth [m]
                                             (0: a depth), speed [m/s] (1: a speed),
                                             0: a heading; Goby3's stop is
                                             $BPRMB,TIME,0,0,2,0,0,1
    vehicle -> payload  $BFACK,TIME,SENTENCE,ITS_TIME,ID,STATUS,,TEXT
                                             each good $BP line answered: 2 processed,
                                             1 not processed (a request the vehicle
                                             does not fly now: why in TEXT), 0 invalid
                        $BFNVG,TIME,LAT,N|S,LON,E|W,Q,ALT,DEPTH,HDG,ROLL,PITCH,CTIME
                        $BFNVR,TIME,VE,VN,VD,PITCHRATE,ROLLRATE,YAWRATE
                                             navigation from the truth, at `nav_rate_hz`
                        $BFMIS,TIME,MISSION,STATUS
                                             1 Hz and at each change: `Running` on its
                                             mission or the payload's, `Aborted`,
                                             `Manual` under an operator
                        $BFCTL,TIME,1|0      control granted or taken back, at each
                                             change (control_sentence: ctl), or
                        $BFMSC,TIME,TEXT     the older firmware's grant (msc: no word
                                             when it takes control back but a $BFMIS
                                             without `Running`)

Nothing is sent before the payload asks for it with $BPLOG (its $BFACK
included). TIME is the simulator's time as hhmmss.sss (sim time 0 is 00:00:00).
The vehicle behind it (sim.frontseat) decides who flies; a request is taken
(status 2) only when the vehicle's control rules (`judge`) let the payload fly
now: a request while control cannot be granted (above control_min_depth_m, an
abort, an operator's override) is answered 1 with the reason, and not flown. The
vehicle takes control back `request_timeout_s` after the newest request (its own
configuration: the request carries no timeout).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from confcheck import setting
from sim.devices import nmea
from sim.devices.emulator import DeviceContext
from sim.devices.frontseat_wire import MANUAL, PAYLOAD, STOPPED, FrontseatProtocol, Request, compose

LOG_IDS = ("ACK", "NVG", "NVR", "MIS", "MSC", "CTL", "SHT")  # what a $BPLOG may turn on (SHT: never sent)
MINUTE_DIGITS = 4  # ddmm.mmmm: 1e-4 minute, some 0.19 m of latitude
MIS_PERIOD_S = 1.0
MISSION_NAME = "sim.mis"
MAX_DEPTH_M = 6000.0
MAX_SPEED_MPS = 10.0
DECIMAL = re.compile(r"-?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)")  # plain decimals: no exponent, no inf, no nan
TIME = re.compile(r"[0-9]{6}(?:\.[0-9]*)?")
ECHO = re.compile(r"[0-9.]{0,16}")
ADDRESS = re.compile(r"BP[A-Z]{3}")  # the payload's sentences

# $BFACK statuses
INVALID, NOT_PROCESSED, PROCESSED = 0, 1, 2


@dataclass
class BluefinOptions:
    # how it says the payload has control: $BFCTL,TIME,1|0 (SPI 1.10 on) or the older
    # firmware's $BFMSC (a grant only: auv-frontseat reads its control back from $BFMIS)
    control_sentence: str = setting("ctl", one_of=("ctl", "msc"))
    nav_rate_hz: float = setting(5.0, ge=0.1, le=50.0, unit="Hz")  # $BFNVG and $BFNVR
    # without a newer request for this long the vehicle takes control back (its own
    # configuration: $BPRMB carries no timeout)
    request_timeout_s: float = setting(5.0, gt=0.0, le=120.0, unit="s")


def time_of(t: float) -> str:
    """hhmmss.sss of sim time t [s] (0: midnight; a day wraps)."""
    ms = round(max(t, 0.0) * 1000.0) % 86_400_000
    s, ms = divmod(ms, 1000)
    return f"{s // 3600:02d}{s // 60 % 60:02d}{s % 60:02d}.{ms:03d}"


def _decimal(text: str) -> float | None:
    return float(text) if DECIMAL.fullmatch(text) else None


class BluefinFrontseat(FrontseatProtocol):
    protocol = "bluefin"
    Options = BluefinOptions
    options: BluefinOptions
    line_max = 600  # as auv-frontseat's framer

    def __init__(self, ctx: DeviceContext) -> None:
        super().__init__(ctx)
        self.logging: set[str] = set()  # the sentences the payload asked for
        self.heartbeats = 0  # $BPSTS heard
        self.payload_ok = True  # its newest heartbeat's word
        self.acks: dict[int, int] = {}  # $BFACK sent, by status
        self.not_processed: dict[str, int] = {}  # requests answered 1, by reason
        self._said_control: bool | None = None  # the grant the payload was last told (None: not yet)
        self._said_status = ""
        self._next_mis = 0.0
        self._next_nav = 0.0

    # ---- the payload's lines

    def sentence(self, fields: list[str], t: float) -> None:
        address = fields[0]
        if not ADDRESS.fullmatch(address):
            self._refuse("unknown sentence")
            return
        kind = address[2:]
        if kind == "LOG":
            self._log(fields, t)
        elif kind == "STS":
            self._sts(fields, t)
        elif kind == "RMB":
            self._rmb(fields, t)
        else:  # $BPABT, $BPKIL, $BPTRM, ...: the payload's other requests
            self._refuse("unsupported sentence")
            self._ack(kind, "", NOT_PROCESSED, "not supported", t)

    def _invalid(self, kind: str, its_time: str, why: str, t: float) -> None:
        self._refuse(f"bad $BP{kind}")
        self._ack(kind, its_time, INVALID, why, t)

    def _log(self, f: list[str], t: float) -> None:
        if len(f) != 3 or f[1] not in LOG_IDS or f[2] not in ("ON", "OFF"):
            self._invalid("LOG", "", "expected a known ID and ON or OFF", t)
            return
        if f[2] == "ON":
            self.logging.add(f[1])
        else:
            self.logging.discard(f[1])
        self._ack("LOG", "", PROCESSED, "", t)
        # what it asks for now it hears now: the grant and the mission as they stand
        if f[1] in ("CTL", "MSC"):
            self._said_control = None
        elif f[1] == "MIS":
            self._next_mis = t

    def _sts(self, f: list[str], t: float) -> None:
        if len(f) < 3 or not TIME.fullmatch(f[1]) or f[2] not in ("0", "1"):
            self._invalid("STS", f[1] if len(f) > 1 else "", "expected a time and 1 or 0", t)
            return
        self.heartbeats += 1
        self.payload_ok = f[2] == "1"
        self._ack("STS", f[1], PROCESSED, "", t)

    def _rmb(self, f: list[str], t: float) -> None:
        its_time = f[1] if len(f) > 1 else ""
        if len(f) != 8 or not TIME.fullmatch(f[1]):
            self._invalid("RMB", its_time, "expected a time and 6 fields", t)
            return
        hdg, depth, speed = (_decimal(x) for x in (f[2], f[3], f[5]))
        modes = (f[4], f[6], f[7])
        if hdg is None or depth is None or speed is None or any(m not in ("0", "1", "2") for m in modes):
            self._invalid("RMB", its_time, "not a number", t)
            return
        stop = modes == ("2", "0", "1") and hdg == 0.0 and depth == 0.0 and speed == 0.0
        if not stop:
            if not (0.0 <= hdg <= 360.0 and 0.0 <= depth <= MAX_DEPTH_M and 0.0 <= speed <= MAX_SPEED_MPS):
                self._invalid("RMB", its_time, "out of range", t)
                return
            if modes != ("0", "1", "0"):  # altitude, pitch, rpm, rudder: not this vehicle's
                self._not_processed(its_time, "only heading depth and speed", t)
                return
        why = self.judge(t)
        if why is not None:
            self._not_processed(its_time, why, t)
            return
        self.request = Request(t, math.radians(hdg % 360.0), depth, speed, self.options.request_timeout_s, stop=stop)
        self.requests += 1
        self._ack("RMB", its_time, PROCESSED, "", t)

    def _not_processed(self, its_time: str, why: str, t: float) -> None:
        self.not_processed[why] = self.not_processed.get(why, 0) + 1
        self._ack("RMB", its_time, NOT_PROCESSED, why, t)

    def _ack(self, kind: str, its_time: str, status: int, text: str, t: float) -> None:
        self.acks[status] = self.acks.get(status, 0) + 1
        if not ECHO.fullmatch(its_time):  # the payload's time echoed only if it is one
            its_time = ""
        if "ACK" in self.logging:
            self._say(f"BFACK,{time_of(t)},{kind},{its_time},,{status},,{text}", t)

    # ---- the vehicle's own lines

    def _say(self, body: str, t: float) -> None:
        self.send(compose(body), t)

    def status_word(self) -> str:
        helm = self.report.helm
        return "Aborted" if helm == STOPPED else "Manual" if helm == MANUAL else "Running"

    def update(self, t: float) -> None:
        if self.silent:
            return
        now = time_of(t)
        granted = self.report.helm == PAYLOAD
        status = self.status_word()
        if self.options.control_sentence == "ctl":
            if "CTL" in self.logging and granted != self._said_control:
                self._say(f"BFCTL,{now},{int(granted)}", t)
                self._said_control = granted
        elif "MSC" in self.logging and granted != self._said_control:
            if granted:  # the older firmware's grant; taken back: only $BFMIS says so
                self._say(f"BFMSC,{now},payload control", t)
            self._said_control = granted
        if "MIS" in self.logging and (status != self._said_status or t >= self._next_mis - 1e-9):
            self._say(f"BFMIS,{now},{MISSION_NAME},{status}", t)
            self._said_status = status
            self._next_mis = t + MIS_PERIOD_S
        if t >= self._next_nav - 1e-9:
            period = 1.0 / self.options.nav_rate_hz
            self._next_nav += period
            if self._next_nav <= t:  # a late step: the next one period on, no burst
                self._next_nav = t + period
            self._navigation(t)

    def _navigation(self, t: float) -> None:
        tr = self.truth
        if tr is None:
            return
        now = time_of(t)
        if "NVG" in self.logging:
            lat, ns = nmea.latitude(tr.latitude_deg, MINUTE_DIGITS)
            lon, ew = nmea.longitude(tr.longitude_deg, MINUTE_DIGITS)
            roll, pitch = math.degrees(tr.eta[3]), math.degrees(tr.eta[4])
            hdg = math.degrees(tr.eta[5]) % 360.0
            self._say(
                f"BFNVG,{now},{lat},{ns},{lon},{ew},1,{tr.altitude_m:.1f},{tr.eta[2]:.2f},"
                f"{hdg:.1f},{roll:.1f},{pitch:.1f},{now}",
                t,
            )
        if "NVR" in self.logging:
            vn, ve, vd = tr.velocity_ned()
            p, q, r = (math.degrees(x) for x in tr.nu[3:6])
            self._say(f"BFNVR,{now},{ve:.2f},{vn:.2f},{vd:.2f},{q:.1f},{p:.1f},{r:.1f}", t)
