"""Team keys for command authentication (docs/security.md): auv-keygen."""
