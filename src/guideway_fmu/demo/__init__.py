"""The main job on built-in data (``job``) and the page that shows all of it (``page``)."""
