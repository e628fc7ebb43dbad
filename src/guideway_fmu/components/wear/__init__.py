"""The Wear FMU: raceway wear and preload loss over the running distance (Zhang, Wang and Jiang)."""
