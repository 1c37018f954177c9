"""The navigation filter's tools: a nav config from a simulator config, a recorded survey to replay."""
