"""The surface radio of the simulated world (docs/radio.md): line of sight
above the waves, range, rate, latency and loss (link.py), run by auv-radio-sim."""
