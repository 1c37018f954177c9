#!/usr/bin/env bash
# Run a command where LCM multicast works and stays on this machine.
#
# By default the command runs in a private network namespace (unshare -rn)
# with only a loopback interface, multicast enabled on it and a route for
# 224.0.0.0/4: LCM then works whatever the host's routing, and test traffic
# can neither leave the machine nor meet another run's (or a user's lcm-spy).
#
# --only-if-needed: run on the host network when it already routes multicast
# (so lcm-spy on the host can watch a demo), else isolate as above.
set -euo pipefail

only_if_needed=0
if [[ "${1:-}" == "--only-if-needed" ]]; then only_if_needed=1; shift; fi

host_routes_multicast() {
    command -v ip >/dev/null && ip route get 239.255.76.67 >/dev/null 2>&1
}

if [[ "${AUV_IN_ISOLATED_NET:-}" == 1 ]]; then
    exec "$@"
fi

if (( only_if_needed )) && host_routes_multicast; then
    exec "$@"
fi

if command -v unshare >/dev/null && command -v ip >/dev/null && unshare -rn true 2>/dev/null; then
    export AUV_IN_ISOLATED_NET=1
    exec unshare -rn bash -c '
        ip link set lo up && ip link set lo multicast on &&
        ip route add 224.0.0.0/4 dev lo || { echo "isolated_net: could not set up loopback multicast" >&2; exit 1; }
        exec "$@"' isolated-net "$@"
fi

echo "isolated_net: private network namespaces are not available here (unshare -rn failed);" \
     "running on the host network" >&2
if ! host_routes_multicast; then
    echo "isolated_net: this host has no multicast route, so LCM cannot start. Fix once with:" >&2
    echo "    sudo ip route add 224.0.0.0/4 dev lo   # or dev <your LAN interface>" >&2
fi
exec "$@"
