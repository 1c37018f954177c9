"""Device emulators: a simulated sensor speaking its device's own protocol on a pty or TCP port (docs/simulator.md, "Devices at the wire")."""
