"""Cases of a bearing given by a description file (``family = "bearing"``): ``flexbearing run`` on any bearing."""
