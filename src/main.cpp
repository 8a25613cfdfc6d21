// bapd: bond-associated NOSB peridynamics for soft materials (placeholder driver).
#include <petscsys.h>

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, "bapd: BA NOSB peridynamics\n"));
  PetscCall(PetscFinalize());
  return 0;
}
