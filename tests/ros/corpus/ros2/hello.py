def main():
    print('Hi from in_class_day02.')


if __name__ == '__main__':
    main()
