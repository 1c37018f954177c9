"""Live bridges from LCM: Foxglove, Zenoh between sites, the link-impairment relay."""
