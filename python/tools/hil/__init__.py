"""Hardware in the loop at the wire (docs/hil.md): each vehicle computer runs
its drivers, auv-nav and managers in its own LCM world and reaches its
simulator only through device links; `links` plans the links and the
simulator's side of them, `vc` is one vehicle computer, `cli` runs a scenario
this way."""
