/* variant_mc_torque.c - placeholder */
int main(void)
{
    return 0;
}
