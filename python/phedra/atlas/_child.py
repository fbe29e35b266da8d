"""The process that evaluates an atlas's designs for a worker (_evaluate.Child)."""

from phedra.atlas._evaluate import child_main

if __name__ == "__main__":
    child_main()
