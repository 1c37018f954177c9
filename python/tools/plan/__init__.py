"""Planners: a survey polygon into lines, plans and a scenario (`auv-plan-survey`), the MCM team's plans."""
