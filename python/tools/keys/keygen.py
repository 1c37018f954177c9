"""auv-keygen: write a team key file for command authentication (docs/security.md).

    auv-keygen FILE [--id KEY_ID]            a new file with one fresh key
    auv-keygen FILE --rotate [--id KEY_ID]   add a fresh key that signs from now on,
                                             keeping the newest old one (it still verifies)
    auv-keygen FILE --retire                 keep only the newest key (the change is over)

The file is created with mode 0600 (every loader refuses a file open to group
or others); a new file never replaces an existing one. The secret is 32 bytes
from the operating system's generator (`secrets`). Exit 0, or 1 with the reason.
"""

from __future__ import annotations

import argparse
import datetime as dt
import os
import secrets
import sys
from pathlib import Path

from auvlcm import auth


def _write(path: Path, keys: list[auth.Key], new: bool) -> None:
    text = "# CHASM-AUV team key file (auv-keygen): KEY_ID HEX_SECRET; every key verifies, the last one signs\n"
    text += "".join(f"{k.id} {k.secret.hex()}\n" for k in keys)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    with os.fdopen(fd, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    if new:
        os.link(tmp, path)  # fails if path exists: a key file is never replaced by a new one
        tmp.unlink()
    else:
        os.replace(tmp, path)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="auv-keygen", description=__doc__.split("\n\n")[0])
    p.add_argument("file", type=Path)
    p.add_argument("--id", help="key id (default team-YYYYMMDD-HHMMSS, UTC)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--rotate", action="store_true", help="add a new signing key, keep the newest old one")
    g.add_argument("--retire", action="store_true", help="keep only the newest key")
    a = p.parse_args(argv)
    kid = a.id or dt.datetime.now(dt.timezone.utc).strftime("team-%Y%m%d-%H%M%S")
    try:
        if len(kid) > auth.MAX_KEY_ID or not kid or not set(kid) <= auth._ID_CHARS:
            raise auth.KeyFileError(f"key id '{kid}': 1 to 32 letters, digits, '_', '-' or '.'")
        if a.rotate or a.retire:
            old = list(auth.load_keys(a.file).keys)
            if a.retire:
                keys = old[-1:]
            else:
                if any(k.id == kid for k in old):
                    raise auth.KeyFileError(f"{a.file}: key id '{kid}' is already in it")
                keys = [*old[-1:], auth.Key(kid, secrets.token_bytes(32))]
            _write(a.file, keys, new=False)
        else:
            if a.file.exists():
                raise auth.KeyFileError(f"{a.file}: exists (use --rotate to add a key to it)")
            keys = [auth.Key(kid, secrets.token_bytes(32))]
            _write(a.file, keys, new=True)
    except (auth.KeyFileError, OSError) as e:
        print(f"auv-keygen: {e}", file=sys.stderr)
        return 1
    print(
        f"auv-keygen: {a.file}: signing key '{keys[-1].id}'"
        + (f", also accepts '{keys[0].id}'" if len(keys) > 1 else "")
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
