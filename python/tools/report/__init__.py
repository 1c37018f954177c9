"""The report of a run from its log (`auv-report`): coverage, detections, the team's figures, plots."""
