"""The surface radio's gateways: the shore's and the vehicle's ends, and the
chunked transfers between them that survive a dive (docs/radio.md)."""
