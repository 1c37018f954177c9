"""Host agents: `auv-agent` runs a host's part on command, `auv-agentctl` commands the agents."""
